#pragma once

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace StabilizedLagrangian
{
  /**
   * @brief Registry of the plug-ins implementing one interface.
   *
   * Each plug-in registers a name (the value a user writes in the `.prm`
   * file), a documentation string, a function declaring its parameters in
   * a subsection named after it, and a factory that builds it from the
   * parsed parameters. The driver only ever asks the registry for a model
   * by the name the user chose; it never switches on that name.
   */
  template <typename InterfaceType> class PluginRegistry
  {
  public:
    using Declare = std::function<void(dealii::ParameterHandler &)>;
    using Create  = std::function<std::unique_ptr<InterfaceType>(const dealii::ParameterHandler &)>;

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
     * @brief Build the plug-in chosen by the `Model` entry of the subsection @p subsection.
     */
    static std::unique_ptr<InterfaceType>
    create_from(dealii::ParameterHandler &prm, const std::string &subsection)
    {
      prm.enter_subsection(subsection);
      std::unique_ptr<InterfaceType> model = create(prm);
      prm.leave_subsection();
      return model;
    }

    /**
     * @brief Build the plug-in chosen by the `Model` entry of the current subsection.
     */
    static std::unique_ptr<InterfaceType>
    create(dealii::ParameterHandler &prm)
    {
      return create(prm.get("Model"), prm);
    }

    /**
     * @brief Build the plug-in @p name from its subsection of the current subsection.
     */
    static std::unique_ptr<InterfaceType>
    create(const std::string &name, dealii::ParameterHandler &prm)
    {
      const auto it = entries().find(name);
      AssertThrow(it != entries().end(),
                  dealii::ExcMessage("Unknown model '" + name + "'; allowed: " + pattern()));
      prm.enter_subsection(name);
      std::unique_ptr<InterfaceType> model = it->second.create(prm);
      prm.leave_subsection();
      return model;
    }

    /**
     * @brief Build the plug-in @p name for a plug-in that declares no parameters.
     */
    static std::unique_ptr<InterfaceType>
    create_without_parameters(const std::string &name)
    {
      const auto it = entries().find(name);
      AssertThrow(it != entries().end(),
                  dealii::ExcMessage("Unknown model '" + name + "'; allowed: " + pattern()));
      return it->second.create(dealii::ParameterHandler());
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
  };

  /**
   * @brief Thrown for invalid user input; main() prints the message and exits non-zero.
   */
  class InputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };
} // namespace StabilizedLagrangian
