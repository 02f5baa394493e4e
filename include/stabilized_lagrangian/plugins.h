#pragma once

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  /**
   * @brief The path of subsection @p name of the subsection @p parent
   * (empty: the top level), as messages name it: `Contact/Zone left`.
   */
  inline std::string
  subsection_path(const std::string &parent, const std::string &name)
  {
    return parent.empty() ? name : parent + "/" + name;
  }

  /**
   * @brief Registry of the plug-ins implementing one interface.
   *
   * Each plug-in registers a name (the value a user writes in the `.prm`
   * file), a documentation string, a function declaring its parameters in
   * a subsection named after it, and a factory that builds it from the
   * parsed parameters of that subsection and its path (e.g. `Contact/Zone
   * left/Friction law/Coulomb`), with which its messages name the entries
   * the user wrote: a plug-in may be chosen in more than one place. The driver only ever asks the
   * registry for a model by the name the user chose; it never switches on that name.
   */
  template <typename InterfaceType> class PluginRegistry
  {
  public:
    using Declare = std::function<void(dealii::ParameterHandler &)>;
    /**
     * builds the plug-in from its subsection (the current one, which it may
     * enter further) and that subsection's path
     */
    using Create = std::function<std::unique_ptr<InterfaceType>(dealii::ParameterHandler &,
                                                                const std::string &)>;

    /**
     * @brief Add a plug-in; called from a static initialiser in the plug-in's file.
     */
    static bool
    add(const std::string &name,
        const std::string &description,
        const Declare     &declare,
        const Create      &create)
    {
      entries()[name] = Entry{description, declare, create};
      return true;
    }

    /**
     * @brief The registered names, in alphabetical order.
     */
    static std::vector<std::string>
    names()
    {
      std::vector<std::string> result;
      for (const auto &entry : entries())
        result.push_back(entry.first);
      return result;
    }

    /**
     * @brief The description the plug-in @p name was registered with.
     */
    static const std::string &
    description(const std::string &name)
    {
      return entry(name).description;
    }

    /**
     * @brief Declare the parameters of the plug-in @p name in the current
     * subsection (for plug-ins chosen by a subsection's name rather than a
     * `Model` entry, any number of times: `Boundary conditions/Neumann top`).
     */
    static void
    declare_parameters_here(const std::string &name, dealii::ParameterHandler &prm)
    {
      entry(name).declare(prm);
    }

    /**
     * @brief Build the plug-in @p name from the current subsection, whose path is @p path.
     */
    static std::unique_ptr<InterfaceType>
    create_here(const std::string &name, dealii::ParameterHandler &prm, const std::string &path)
    {
      return entry(name).create(prm, path);
    }

    /**
     * @brief The registered names joined by `|`, for a Patterns::Selection.
     */
    static std::string
    pattern()
    {
      std::string result;
      for (const auto &entry : entries())
        result += (result.empty() ? "" : "|") + entry.first;
      return result;
    }

    /**
     * @brief Documentation listing every plug-in with its description.
     */
    static std::string
    documentation(const std::string &intro)
    {
      std::string result = intro;
      for (const auto &entry : entries())
        result += "\n  '" + entry.first + "': " + entry.second.description;
      return result;
    }

    /**
     * @brief Declare a `Model` selection and one subsection per plug-in.
     */
    static void
    declare_parameters(dealii::ParameterHandler &prm,
                       const std::string        &default_model,
                       const std::string        &intro)
    {
      prm.declare_entry(
          "Model", default_model, dealii::Patterns::Selection(pattern()), documentation(intro));
      for (const auto &entry : entries())
        {
          prm.enter_subsection(entry.first);
          entry.second.declare(prm);
          prm.leave_subsection();
        }
    }

    /**
     * @brief declare_parameters() inside the subsection @p subsection.
     */
    static void
    declare_parameters_in(dealii::ParameterHandler &prm,
                          const std::string        &subsection,
                          const std::string        &default_model,
                          const std::string        &intro)
    {
      prm.enter_subsection(subsection);
      declare_parameters(prm, default_model, intro);
      prm.leave_subsection();
    }

    /**
     * @brief Build the plug-in chosen by the `Model` entry of the subsection
     * @p subsection of the current subsection, whose path is @p path (empty:
     * the top level).
     */
    static std::unique_ptr<InterfaceType>
    create_from(dealii::ParameterHandler &prm,
                const std::string        &subsection,
                const std::string        &path = "")
    {
      prm.enter_subsection(subsection);
      std::unique_ptr<InterfaceType> model = create(prm, subsection_path(path, subsection));
      prm.leave_subsection();
      return model;
    }

    /**
     * @brief Build the plug-in chosen by the `Model` entry of the current
     * subsection, whose path is @p path.
     */
    static std::unique_ptr<InterfaceType>
    create(dealii::ParameterHandler &prm, const std::string &path)
    {
      return create(prm.get("Model"), prm, path);
    }

    /**
     * @brief Build the plug-in @p name from its subsection of the current
     * subsection, whose path is @p path.
     */
    static std::unique_ptr<InterfaceType>
    create(const std::string &name, dealii::ParameterHandler &prm, const std::string &path)
    {
      const Entry &model_entry = entry(name);
      prm.enter_subsection(name);
      std::unique_ptr<InterfaceType> model = model_entry.create(prm, subsection_path(path, name));
      prm.leave_subsection();
      return model;
    }

    /**
     * @brief Build the plug-in @p name for a plug-in that declares no parameters.
     */
    static std::unique_ptr<InterfaceType>
    create_without_parameters(const std::string &name)
    {
      dealii::ParameterHandler none;
      return entry(name).create(none, name);
    }

  private:
    struct Entry
    {
      std::string description;
      Declare     declare;
      Create      create;
    };

    static std::map<std::string, Entry> &
    entries()
    {
      static std::map<std::string, Entry> map;
      return map;
    }

    static const Entry &
    entry(const std::string &name)
    {
      const auto it = entries().find(name);
      AssertThrow(it != entries().end(),
                  dealii::ExcMessage("Unknown model '" + name + "'; allowed: " + pattern()));
      return it->second;
    }
  };

  namespace internal
  {
    /**
     * @brief Register @p PluginType in the registry of @p InterfaceType: its
     * parameters are declared by `PluginType::declare_parameters(prm)` and it is
     * built by the constructor `PluginType(const ParameterHandler &, const
     * std::string &section)`, which reads the plug-in's own subsection and
     * names its entries from @p section, that subsection's path.
     */
    template <typename InterfaceType, typename PluginType>
    bool
    register_plugin(const std::string &name, const std::string &description)
    {
      return PluginRegistry<InterfaceType>::add(
          name,
          description,
          &PluginType::declare_parameters,
          [](dealii::ParameterHandler &prm,
             const std::string        &section) -> std::unique_ptr<InterfaceType> {
            return std::make_unique<PluginType>(prm, section);
          });
    }

    /**
     * @brief register_plugin() for the plug-ins of a dimension-dependent
     * interface: registers `PluginTemplate<dim>` for dim = 2 and 3.
     */
    template <template <int> class InterfaceTemplate, template <int> class PluginTemplate>
    bool
    register_plugin(const std::string &name, const std::string &description)
    {
      register_plugin<InterfaceTemplate<2>, PluginTemplate<2>>(name, description);
      return register_plugin<InterfaceTemplate<3>, PluginTemplate<3>>(name, description);
    }

    /**
     * @brief Register a plug-in that declares no parameters, built as
     * `PluginType(constructor_arguments...)`.
     */
    template <typename InterfaceType, typename PluginType, typename... Arguments>
    bool
    register_plugin_without_parameters(const std::string &name,
                                       const std::string &description,
                                       const Arguments &...constructor_arguments)
    {
      return PluginRegistry<InterfaceType>::add(
          name,
          description,
          [](dealii::ParameterHandler &) {},
          [=](dealii::ParameterHandler &, const std::string &) -> std::unique_ptr<InterfaceType> {
            return std::make_unique<PluginType>(constructor_arguments...);
          });
    }

    /**
     * @brief register_plugin_without_parameters() for dim = 2 and 3.
     */
    template <template <int> class InterfaceTemplate,
              template <int>
              class PluginTemplate,
              typename... Arguments>
    bool
    register_plugin_without_parameters(const std::string &name,
                                       const std::string &description,
                                       const Arguments &...constructor_arguments)
    {
      register_plugin_without_parameters<InterfaceTemplate<2>, PluginTemplate<2>>(
          name, description, constructor_arguments...);
      return register_plugin_without_parameters<InterfaceTemplate<3>, PluginTemplate<3>>(
          name, description, constructor_arguments...);
    }
  } // namespace internal

  /**
   * @brief Thrown for invalid user input; main() prints the message and exits non-zero.
   */
  class InputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };
} // namespace StabilizedLagrangian

#define SL_PLUGIN_CONCATENATE_(a, b) a##b
#define SL_PLUGIN_CONCATENATE(a, b) SL_PLUGIN_CONCATENATE_(a, b)

/**
 * @brief Register a plug-in in one line, at namespace scope of its `.cc` file:
 *
 *     SL_REGISTER_PLUGIN(Interface, LinearElastic, "linear elastic", "isotropic ...");
 *
 * @p name is the value of the `Model` entry that selects the plug-in (and the
 * name of its subsection), @p description its documentation. The plug-in
 * provides `static void declare_parameters(ParameterHandler &)` and a
 * constructor from the `const ParameterHandler &` of its subsection and that
 * subsection's path (`const std::string &`, for its messages). When
 * @p interface and @p plugin are class templates over the dimension, the
 * plug-in is registered for dim = 2 and 3.
 */
#define SL_REGISTER_PLUGIN(interface, plugin, name, description)                              \
  [[maybe_unused]] static const bool SL_PLUGIN_CONCATENATE(sl_plugin_registered_, __LINE__) = \
      ::StabilizedLagrangian::internal::register_plugin<interface, plugin>(name, description)

/**
 * @brief Register in one line a plug-in that declares no parameters and is
 * built from fixed constructor arguments (the FE pairs), for dim = 2 and 3
 * when @p interface and @p plugin are class templates over the dimension:
 *
 *     SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(FEPair, LagrangeFacePair, "Q1/P1", "...", 1, 1, true);
 */
#define SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(interface, plugin, name, description, ...)       \
  [[maybe_unused]] static const bool SL_PLUGIN_CONCATENATE(sl_plugin_registered_, __LINE__) =  \
      ::StabilizedLagrangian::internal::register_plugin_without_parameters<interface, plugin>( \
          name, description, __VA_ARGS__)
