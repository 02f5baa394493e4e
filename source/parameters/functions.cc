#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/plugins.h>

#include <algorithm>
#include <cmath>
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
      const std::vector<std::string> variables =
          Utilities::split_string_list(prm.get("Variable names"));
      if (variables.size() != dim + 1)
        throw InputError(entry + "/Variable names = '" + prm.get("Variable names") + "': a " +
                         std::to_string(dim) + "D function needs " + std::to_string(dim + 1) +
                         " variable names, the coordinates then time, e.g. '" +
                         (dim == 2 ? "x,y,t" : "x,y,z,t") + "'.");
      for (const auto &constant : Utilities::split_string_list(prm.get("Function constants")))
        {
          const std::string constant_name = Utilities::trim(constant.substr(0, constant.find('=')));
          if (std::find(variables.begin(), variables.end(), constant_name) != variables.end())
            throw InputError(entry + "/Function constants: '" + constant_name +
                             "' is also a variable name (" + prm.get("Variable names") +
                             "); give the constant another name.");
        }
      const std::string cannot_parse =
          entry + ": the function could not be parsed (" + std::to_string(n_components) +
          " components separated by ';', variables x, y" + (dim == 3 ? ", z" : "") +
          ", t, constants 'name=value, ...').";
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
