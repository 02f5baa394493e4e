#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/plugins.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <sstream>

/** @file The functions of the time and the coordinates a `.prm` gives (BoundaryFunction). */

namespace StabilizedLagrangian
{
  namespace Parameters
  {
    template <int dim>
    void
    declare_function(ParameterHandler  &prm,
                     const std::string &unit,
                     const unsigned int n_components)
    {
      const std::string coordinates = dim == 2 ? "x,y,t" : "x,y,z,t";
      std::string       zeros       = "0";
      for (unsigned int c = 1; c < n_components; ++c)
        zeros += "; 0";
      prm.declare_entry("Function expression",
                        zeros,
                        Patterns::Anything(),
                        std::to_string(n_components) + " components (" + unit +
                            ") separated by ';', of the coordinates and the time (muparser: "
                            "+ - * / ^, sin, exp, sqrt, min, max, if(condition, a, b), ...).");
      prm.declare_entry("Function constants",
                        "",
                        Patterns::Anything(),
                        "Names for values in the expression: 'name=value, ...'.");
      prm.declare_entry("Variable names",
                        coordinates,
                        Patterns::Anything(),
                        "The names of the coordinates and the time in the expression.");
    }

    template <int dim>
    BoundaryFunction<dim>::BoundaryFunction(const std::string &entry,
                                            const unsigned int n_components)
        : Functions::ParsedFunction<dim>(n_components)
        , entry(entry)
    {
    }

    template <int dim>
    void
    BoundaryFunction<dim>::vector_value(const Point<dim> &point, Vector<double> &values) const
    {
      Functions::ParsedFunction<dim>::vector_value(point, values);
      for (unsigned int c = 0; c < values.size(); ++c)
        note(point, values[c], c);
    }

    template <int dim>
    double
    BoundaryFunction<dim>::value(const Point<dim> &point, const unsigned int component) const
    {
      const double result = Functions::ParsedFunction<dim>::value(point, component);
      note(point, result, component);
      return result;
    }

    template <int dim>
    void
    BoundaryFunction<dim>::note(const Point<dim>  &point,
                                const double       value,
                                const unsigned int component) const
    {
      if (std::isfinite(value) || !failure.empty())
        return;
      std::ostringstream message;
      message << entry << ": the function gives " << value << " in component " << component + 1
              << " at t = " << this->get_time() << ", point (" << point
              << "); boundary data must be finite there.";
      failure = message.str();
    }

    template <int dim>
    void
    BoundaryFunction<dim>::check_finite(const MPI_Comm communicator) const
    {
      if (Utilities::MPI::max(static_cast<int>(!failure.empty()), communicator) == 0)
        return;
      std::string first;
      for (const auto &message : Utilities::MPI::all_gather(communicator, failure))
        if (first.empty())
          first = message;
      failure.clear();
      throw InputError(first);
    }

    namespace
    {
      /** Whether @p text is a name muparser takes: a letter or _, then letters, digits or _. */
      bool
      is_name(const std::string &text)
      {
        static const std::regex name("[A-Za-z_][A-Za-z0-9_]*");
        return std::regex_match(text, name);
      }

      /**
       * The entries of the function subsection @p entry that @p prm is in,
       * checked one by one so that an error names the one at fault:
       * `Variable names` (dim + 1 distinct names), `Function constants`
       * ('name=value, ...', each value a finite number, no name a variable's)
       * and the number of components of `Function expression`.
       */
      template <int dim>
      void
      check_function_entries(const ParameterHandler &prm,
                             const std::string      &entry,
                             const unsigned int      n_components)
      {
        const std::string              names     = prm.get("Variable names");
        const std::vector<std::string> variables = Utilities::split_string_list(names);
        const std::string              example   = dim == 2 ? "x,y,t" : "x,y,z,t";
        if (variables.size() != dim + 1)
          throw InputError(entry + "/Variable names = '" + names + "': a " + std::to_string(dim) +
                           "D function needs " + std::to_string(dim + 1) +
                           " variable names, the coordinates then time, e.g. '" + example + "'.");
        for (const auto &variable : variables)
          if (!is_name(variable) || std::count(variables.begin(), variables.end(), variable) > 1)
            throw InputError(entry + "/Variable names = '" + names + "': '" + variable + "' is " +
                             (is_name(variable) ? "given twice" : "not a name") +
                             "; the variables are " + std::to_string(dim + 1) +
                             " distinct names (a letter or _, then letters, digits or _), the "
                             "coordinates then time, e.g. '" +
                             example + "'.");
        const std::string constants = prm.get("Function constants");
        for (const auto &constant : Utilities::split_string_list(constants))
          {
            const std::string constant_name =
                Utilities::trim(constant.substr(0, constant.find('=')));
            const std::string value =
                constant.find('=') == std::string::npos
                    ? ""
                    : Utilities::trim(constant.substr(constant.find('=') + 1));
            char        *end    = nullptr;
            const double number = std::strtod(value.c_str(), &end);
            if (!is_name(constant_name) || value.empty() || *end != '\0' || !std::isfinite(number))
              throw InputError(entry + "/Function constants = '" + constants + "': '" + constant +
                               "' is not 'name=value' with a name (a letter or _, then letters, "
                               "digits or _) and a finite number; e.g. 'd=0.01, w=2'.");
            if (std::find(variables.begin(), variables.end(), constant_name) != variables.end())
              throw InputError(entry + "/Function constants: '" + constant_name +
                               "' is also a variable name (" + names +
                               "); give the constant another name.");
          }
        const std::string expression = prm.get("Function expression");
        const auto        components = Utilities::split_string_list(expression, ';').size();
        if (components != n_components)
          throw InputError(entry + "/Function expression = '" + expression +
                           "': " + std::to_string(n_components) +
                           " component(s) separated by ';' are needed, got " +
                           std::to_string(components) + ".");
      }
    } // namespace

    template <int dim>
    std::shared_ptr<BoundaryFunction<dim>>
    parse_function(ParameterHandler  &prm,
                   const std::string &parent,
                   const std::string &name,
                   const unsigned int n_components)
    {
      const std::string entry    = parent + "/" + name;
      auto              function = std::make_shared<BoundaryFunction<dim>>(entry, n_components);
      prm.enter_subsection(name);
      check_function_entries<dim>(prm, entry, n_components);
      const std::string cannot_parse =
          entry + "/Function expression = '" + prm.get("Function expression") +
          "': the expression could not be parsed (" + std::to_string(n_components) +
          " components separated by ';', of the variables " + prm.get("Variable names") +
          " and the constants of `Function constants`; muparser syntax).";
      try
        {
          function->parse_parameters(prm);
          // the expression is compiled at its first evaluation: an undefined
          // name shows up here, before anything is written, not mid-run. The
          // probe point need not be on the boundary, so its value is not checked.
          Vector<double> probe(n_components);
          function->Functions::ParsedFunction<dim>::vector_value(Point<dim>(), probe);
        }
      catch (const ExceptionBase &e)
        {
          std::ostringstream message;
          e.print_info(message);
          throw InputError(cannot_parse + " " + Utilities::trim(message.str()));
        }
      catch (...)
        {
          // the expression parser's own exceptions are not std::exceptions
          throw InputError(cannot_parse);
        }
      prm.leave_subsection();
      return function;
    }

    template std::shared_ptr<BoundaryFunction<2>>
    parse_function<2>(ParameterHandler &, const std::string &, const std::string &, unsigned int);
    template std::shared_ptr<BoundaryFunction<3>>
    parse_function<3>(ParameterHandler &, const std::string &, const std::string &, unsigned int);
    template void
    declare_function<2>(ParameterHandler &, const std::string &, unsigned int);
    template void
    declare_function<3>(ParameterHandler &, const std::string &, unsigned int);
    template class BoundaryFunction<2>;
    template class BoundaryFunction<3>;
  } // namespace Parameters
} // namespace StabilizedLagrangian
