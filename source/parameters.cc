#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/contact/friction_law.h>
#include <stabilized_lagrangian/discretization/fe_pair.h>
#include <stabilized_lagrangian/geometry/scene.h>
#include <stabilized_lagrangian/materials/material.h>
#include <stabilized_lagrangian/obstacles/obstacle.h>
#include <stabilized_lagrangian/parameters.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <map>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace Parameters
  {
    std::optional<types::boundary_id>
    boundary_id_or_name(const std::string &entry, const std::string &name)
    {
      if (entry.empty())
        throw InputError(name + ": an empty boundary.");
      if (entry.find_first_not_of("0123456789") != std::string::npos)
        return std::nullopt;
      const unsigned long id = std::stoul(entry);
      if (id >= numbers::internal_face_boundary_id)
        throw InputError(name + " = " + entry + ": a boundary id must be below " +
                         std::to_string(numbers::internal_face_boundary_id) + ".");
      return static_cast<types::boundary_id>(id);
    }

    void
    Contact::declare_parameters(ParameterHandler  &prm,
                                const std::string &fe_pairs,
                                const std::string &fe_pair_documentation)
    {
      prm.enter_subsection("Contact");
      prm.declare_entry("Contact boundary ids",
                        "2",
                        Patterns::List(Patterns::Anything(), 1),
                        "Boundaries of the slave contact surface Γc, which carries the "
                        "multipliers: boundary ids, or names of the mesh's boundaries (the "
                        "physical groups of a Gmsh mesh).");
      prm.declare_entry("Master boundary ids",
                        "",
                        Patterns::List(Patterns::Anything(), 0),
                        "Boundaries of the master surface of a second deformable body (ids or "
                        "names): each slave point is paired with the closest point of the "
                        "deformed master surface. Empty: the master is the rigid `Obstacle`.");
      prm.declare_entry(
          "Master surface search",
          "distributed",
          Patterns::Selection("distributed|replicated"),
          "How the ranks find the master faces of their slave points (doc/formulation.md, "
          "\"Distributed contact search\"). distributed: a rank holds only the master faces "
          "that come within the search distance of its own slave faces, gathered from their "
          "owners as the bodies move (memory per rank: its share and the faces near it). "
          "replicated: every rank holds the whole master surface (memory per rank grows with "
          "the surface; for comparison). Both give the same pairings within the search "
          "distance.");
      prm.declare_entry("Search distance",
                        "0",
                        Patterns::Double(0.),
                        "With Master surface search = distributed: the distance (mm) from a "
                        "rank's deformed slave faces within which it holds every master face; "
                        "slave points further than that from the master surface are paired with "
                        "the nearest face held, or open. 0: twice the largest diameter of the "
                        "contact faces (slave and master).");
      prm.declare_entry("r_n",
                        "1e4",
                        Patterns::Anything(),
                        "Normal augmentation parameter r_n > 0 (N/mm^3), or `automatic`: "
                        "r_n = C_n E / h from the Young's modulus E of the material and the "
                        "largest face diameter h on Γc (doc/robustness.md gives C_n).");
      prm.declare_entry("r_t",
                        "1",
                        Patterns::Anything(),
                        "Tangential augmentation parameter r_t > 0 (1/mm), or `automatic`: "
                        "r_t = C_t / l with l the largest displacement increment the Dirichlet "
                        "data prescribe over one load step (h without prescribed motion): "
                        "r_t l, not μ/h, sets the good range (doc/robustness.md gives C_t).");
      prm.declare_entry("Automatic r_n factor",
                        "1",
                        Patterns::Double(),
                        "With r_n = automatic: a factor > 0 on the automatic value (to scan "
                        "around it).");
      prm.declare_entry("Automatic r_t factor",
                        "1",
                        Patterns::Double(),
                        "With r_t = automatic: a factor > 0 on the automatic value.");
      prm.declare_entry(
          "Finite element pair", "Q1/P1", Patterns::Selection(fe_pairs), fe_pair_documentation);
      prm.declare_entry(
          "Contact quadrature",
          "Gauss-Lobatto",
          Patterns::Selection("Gauss|Gauss-Lobatto"),
          "Quadrature on Γc; the contact and stick/slip statuses live at its "
          "points. Gauss-Lobatto (degree max(k, m) + 1 points per direction) puts them "
          "at the multiplier nodes when m >= k.");
      prm.declare_entry(
          "Complementarity",
          "automatic",
          Patterns::Selection("automatic|pointwise|weighted"),
          "Where the contact and friction conditions hold. pointwise: at every contact "
          "integration point, on lambda_n - r_n g_n (the seed's formulation; its discrete "
          "solution depends on r_n where the multiplier nodes are not the integration points, "
          "e.g. on non-matching meshes: on prm/patin_deformable_block.prm r_n factor 100 moves "
          "the nodal pressures by 1.8 x the peak against factor 1). weighted: once per "
          "multiplier node j on the weighted gap and slip, g_j = int psi_j g_n / int psi_j and "
          "likewise the slip increment (mortar conditions): lambda_j >= 0, g_j >= 0, lambda_j "
          "g_j = 0 and Coulomb's law per node, whose discrete solution does not depend on r_n or "
          "r_t (the same sweep: 1e-13 of the peak); the displacement sees the multiplier field "
          "itself. Needs every multiplier node of the contact surface free (no hanging node on "
          "it, no multiplier on a coarser mesh) and no contact zones. automatic: weighted for "
          "two deformable bodies and for dual pairs, pointwise against a rigid obstacle (the "
          "seed's formulation, which its results are compared with) and wherever weighted "
          "does not apply (contact zones, constrained multiplier nodes, local refinement of a 3D "
          "contact surface); the log and run_summary.csv (weighted_complementarity) give the "
          "choice (doc/formulation.md, \"Which conditions by default\").");
      prm.declare_entry("Check inf-sup",
                        "false",
                        Patterns::Bool(),
                        "Compute the discrete inf-sup constant beta_h of the pair on the run's "
                        "mesh before each refinement cycle's load path (as `--inf-sup`, one MPI "
                        "rank: skipped with a note on more), write it to refinement_cycles.csv "
                        "and run_summary.csv (inf_sup_beta), and warn when it is zero or falls "
                        "under refinement (below 0.8 of its largest earlier value): the pair is "
                        "then not inf-sup stable and the multipliers oscillate. One solve per "
                        "normal multiplier and a dense eigenproblem of their number: for "
                        "checking a pair, not for every production run.");
      FrictionLaws::declare_parameters(prm);
      prm.leave_subsection();
    }

    void
    Contact::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      const auto parse_boundaries = [&prm](const std::string            &entry,
                                           std::set<types::boundary_id> &ids,
                                           std::vector<std::string>     &names) {
        ids.clear();
        names.clear();
        for (const auto &item : Utilities::split_string_list(prm.get(entry)))
          {
            const auto id = boundary_id_or_name(item, "Contact/" + entry);
            if (id)
              ids.insert(*id);
            else
              names.push_back(item);
          }
      };
      parse_boundaries("Contact boundary ids", boundary_ids, boundary_names);
      parse_boundaries("Master boundary ids", master_ids, master_names);
      replicated_search = prm.get("Master surface search") == "replicated";
      search_distance   = prm.get_double("Search distance");
      // a positive number, or `automatic` (times a positive factor)
      const auto parse_parameter = [&prm](const std::string &name,
                                          const std::string &unit,
                                          double            &value,
                                          bool              &automatic,
                                          double            &factor) {
        const std::string text = Utilities::trim(prm.get(name));
        automatic              = text == "automatic";
        factor                 = prm.get_double("Automatic " + name + " factor");
        if (!(factor > 0.) || !std::isfinite(factor))
          throw InputError("Contact/Automatic " + name + " factor must be > 0, got " +
                           prm.get("Automatic " + name + " factor") + ".");
        if (automatic)
          return;
        std::size_t end = 0;
        try
          {
            value = std::stod(text, &end);
          }
        catch (const std::exception &)
          {
            end = 0;
          }
        if (end == 0 || end != text.size() || !(value > 0.) || !std::isfinite(value))
          throw InputError("Contact/" + name + " must be a number > 0 (" + unit +
                           ") or `automatic`, got '" + text + "'.");
      };
      parse_parameter("r_n", "N/mm^3", r_n, r_n_automatic, r_n_factor);
      parse_parameter("r_t", "1/mm", r_t, r_t_automatic, r_t_factor);
      fe_pair       = prm.get("Finite element pair");
      check_inf_sup = prm.get_bool("Check inf-sup");
      quadrature    = prm.get("Contact quadrature") == "Gauss" ? ContactQuadrature::gauss
                                                               : ContactQuadrature::gauss_lobatto;
      complementarity_automatic = prm.get("Complementarity") == "automatic";
      // with `automatic`, pointwise until the run chooses (ContactProblem::choose_complementarity)
      complementarity = prm.get("Complementarity") == "weighted" ? Complementarity::weighted
                                                                 : Complementarity::pointwise;
      prm.leave_subsection();
    }

    namespace
    {
      /** The kinds of `Boundary conditions` subsections with their descriptions, for messages. */
      std::string
      condition_kinds_described()
      {
        std::string result;
        for (const auto &kind : StabilizedLagrangian::BoundaryConditions::kinds())
          result += (result.empty() ? "'" : ", '") + kind + " <name>' (" +
                    StabilizedLagrangian::BoundaryConditions::Registry<2>::description(kind) + ")";
        return result;
      }
    } // namespace

    ConditionSections
    condition_sections(const std::string &text)
    {
      ConditionSections        sections;
      std::vector<std::string> path;
      std::istringstream       lines(text);
      std::string              line, joined;
      while (std::getline(lines, line))
        {
          // ParameterHandler's syntax: '#' starts a comment, a trailing backslash continues a line
          line = Utilities::trim(line.substr(0, line.find('#')));
          if (!line.empty() && line.back() == '\\')
            {
              joined += line.substr(0, line.size() - 1) + " ";
              continue;
            }
          line = Utilities::trim(joined + line);
          joined.clear();
          if (line == "end")
            {
              if (!path.empty())
                path.pop_back();
              continue;
            }
          if (line.rfind("subsection", 0) != 0 || line.size() < 11 ||
              !std::isspace(static_cast<unsigned char>(line[10])))
            continue;
          const std::string name = Utilities::trim(line.substr(10));
          if (path.size() == 1 && path[0] == "Boundary conditions")
            {
              std::vector<std::string> *list = nullptr;
              std::string               label;
              for (const auto &kind : StabilizedLagrangian::BoundaryConditions::kinds())
                if (name.rfind(kind + " ", 0) == 0)
                  {
                    list  = &sections.conditions[kind];
                    label = Utilities::trim(name.substr(kind.size() + 1));
                  }
              if (list == nullptr || label.empty())
                throw InputError(
                    "Boundary conditions/" + name + ": a boundary condition is a subsection " +
                    condition_kinds_described() + ", with any name, e.g. 'Dirichlet top'.");
              if (std::find(list->begin(), list->end(), label) == list->end())
                list->push_back(label);
            }
          if (path.size() == 1 && path[0] == "Contact" && name.rfind("Zone ", 0) == 0)
            {
              const std::string zone = Utilities::trim(name.substr(5));
              if (std::find(sections.zones.begin(), sections.zones.end(), zone) ==
                  sections.zones.end())
                sections.zones.push_back(zone);
            }
          path.push_back(name);
        }
      return sections;
    }

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

    void
    declare_contact_zones(ParameterHandler &prm, const std::vector<std::string> &names)
    {
      prm.enter_subsection("Contact");
      for (const auto &name : names)
        if (!prm.subsection_path_exists({"Zone " + name}))
          {
            prm.enter_subsection("Zone " + name);
            prm.declare_entry("Boundary ids",
                              "",
                              Patterns::Anything(),
                              "Contact boundaries (ids or names, some of `Contact boundary ids`) "
                              "whose friction law is this zone's `Friction law` instead of "
                              "Contact/Friction law; empty: the zone is unused.");
            FrictionLaws::declare_parameters(prm);
            prm.leave_subsection();
          }
      prm.leave_subsection();
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

    void
    LoadStepping::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Load stepping");
      prm.declare_entry(
          "End time", "1", Patterns::Double(), "Pseudo-time at the end of the load path, > 0.");
      prm.declare_entry("Number of load steps",
                        "10",
                        Patterns::Integer(1),
                        "Equal load steps up to the end time.");
      prm.declare_entry("Maximum step cuts",
                        "5",
                        Patterns::Integer(0, 30),
                        "A load step that fails is halved and retried, down to the nominal step "
                        "halved this many times; after a converged step the step doubles back "
                        "towards the nominal one. A failure at the smallest step ends the run "
                        "(exit code 2).");
      prm.declare_entry("Wall time limit",
                        "0",
                        Patterns::Double(0.),
                        "Seconds of wall time after which the run stops cleanly at the end of "
                        "the load step that passes it (exit code 3), the results of the "
                        "converged steps kept; with `Output/Checkpoint interval` > 0 it writes a "
                        "checkpoint first, so that `--resume` continues the run. After the first "
                        "step the log warns when the load path will not fit. 0: no limit.");
      prm.leave_subsection();
    }

    void
    LoadStepping::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Load stepping");
      end_time        = prm.get_double("End time");
      n_steps         = prm.get_integer("Number of load steps");
      max_cuts        = prm.get_integer("Maximum step cuts");
      wall_time_limit = prm.get_double("Wall time limit");
      if (!(end_time > 0.))
        throw InputError("Load stepping/End time must be > 0.");
      prm.leave_subsection();
    }

    void
    NonlinearSolver::declare_parameters(ParameterHandler &prm)
    {
      const auto declare_method = [&prm](const std::string &what) {
        prm.declare_entry("Method",
                          "fixed point",
                          Patterns::Selection("fixed point|newton"),
                          "fixed point: " + what +
                              " is frozen in the inner loops and updated between them "
                              "(the seed's nested algorithm); newton: it is evaluated at every "
                              "Newton iterate and linearised in the Jacobian (generalized "
                              "Newton), and this loop runs once per step.");
      };
      prm.enter_subsection("Nonlinear solver");
      prm.declare_entry("Maximum Newton iterations per load step",
                        "2000",
                        Patterns::Integer(1),
                        "Budget of Newton iterations over all the loops of one load step: "
                        "a step that needs more fails (and is cut), so cycling fixed points end "
                        "quickly.");
      prm.declare_entry("Stopping",
                        "fixed",
                        Patterns::Selection("fixed|adaptive"),
                        "fixed: each loop stops at its own criterion (Newton at its "
                        "`Tolerance`, the friction and geometry loops at theirs, the status "
                        "loop when no status changes). adaptive: each also stops as soon as its "
                        "error is below `Adaptive stopping fraction` of the discretisation error "
                        "estimated at the iterate (after Ern and Vohralik's adaptive inexact "
                        "Newton methods): the energy norm of its last change (Newton's update, "
                        "an outer loop's change of the displacement) against the residual "
                        "error estimate, and its own relative measure (Newton's scaled "
                        "residual, the friction threshold's and the displacement's relative "
                        "changes) against the estimate relative to the solution's energy norm "
                        "(doc/formulation.md, \"Adaptive stopping\"). An iteration that cannot "
                        "change the answer beyond the mesh's own error is not made.");
      prm.declare_entry("Adaptive stopping fraction",
                        "0.02",
                        Patterns::Double(0., 1.),
                        "Stopping = adaptive: the fraction γ of the estimated discretisation "
                        "error that a loop's error must be below. The residual estimate "
                        "overestimates the error by 3-7 (doc/error_estimator.md), so 0.02 keeps "
                        "the loops' error near a tenth of the true discretisation error.");
      prm.declare_entry(
          "Predictor",
          "tangent",
          Patterns::Selection("tangent|extrapolation"),
          "Where each load step's iterations start. tangent: at the last converged state, "
          "the first Newton iteration linearised about it with the step's Dirichlet "
          "increment (the seed's start). extrapolation: at the last converged state plus "
          "the last load step's change of every unknown (displacement, contact pressure, "
          "friction multiplier) scaled to this step's size, so that a steady motion (a "
          "die sliding, a load growing linearly) starts near its answer and with its "
          "contact statuses; the Dirichlet values left over, if any, are then taken by the "
          "tangent step. The first step of a load path, and the first after a mesh change, "
          "start as with tangent (doc/formulation.md, \"Predictor\").");
      prm.enter_subsection("Geometry loop");
      declare_method("the pairing (closest point, normal and tangents)");
      prm.declare_entry("Maximum iterations", "10", Patterns::Integer(1));
      prm.declare_entry("Tolerance",
                        "1e-4",
                        Patterns::Double(0.),
                        "Stop when max|u_k − u_{k−1}| / max|u_k| is at most this (seed §3).");
      prm.leave_subsection();
      prm.enter_subsection("Friction loop");
      declare_method("the friction threshold s = μ λ_n");
      prm.declare_entry("Maximum iterations", "30", Patterns::Integer(1));
      prm.declare_entry("Tolerance",
                        "1e-4",
                        Patterns::Double(0.),
                        "Stop when max|s_new − s_old| / max|s_new| is at most this (seed §3).");
      prm.leave_subsection();
      prm.enter_subsection("Status loop");
      declare_method("the contact status χ of every point");
      prm.declare_entry("Maximum iterations",
                        "30",
                        Patterns::Integer(1),
                        "Stops when no contact point changes status (seed §3).");
      prm.leave_subsection();
      prm.enter_subsection("Newton");
      prm.declare_entry("Maximum iterations", "25", Patterns::Integer(1));
      prm.declare_entry("Tolerance",
                        "1e-8",
                        Patterns::Double(0.),
                        "Newton stops when the measure chosen by `Residual` is at most this.");
      prm.declare_entry(
          "Residual",
          "scaled",
          Patterns::Selection("scaled|absolute|relative"),
          "scaled: each block of the residual against its own scale, dimensionless: the "
          "force rows (max norm) against the largest nodal internal or external force, "
          "the contact and friction rows as lengths (a gap, a stick point's slip) against "
          "the largest displacement; independent of r_n, r_t and of the load level, and "
          "far above round-off (doc/formulation.md). absolute: the seed's criterion, the "
          "residual in N (multiplier rows scaled by r_n and r_t; the seed uses Tolerance "
          "= 1e-6), which sits at the round-off floor when forces are large. relative: "
          "that residual against the first one of the Newton loop.");
      prm.declare_entry("Line search steps",
                        "5",
                        Patterns::Integer(0),
                        "Backtracking: the Newton step is halved at most this many times "
                        "while the residual does not decrease (or a material point leaves "
                        "its admissible range); 0 takes every full step.");
      prm.leave_subsection();
      prm.leave_subsection();
    }

    void
    NonlinearSolver::parse_parameters(ParameterHandler &prm)
    {
      const auto method = [&prm]() {
        return prm.get("Method") == "newton" ? LoopMethod::newton : LoopMethod::fixed_point;
      };
      prm.enter_subsection("Nonlinear solver");
      max_newton_per_step = prm.get_integer("Maximum Newton iterations per load step");
      adaptive_stopping   = prm.get("Stopping") == "adaptive";
      adaptive_fraction   = prm.get_double("Adaptive stopping fraction");
      extrapolate         = prm.get("Predictor") == "extrapolation";
      prm.enter_subsection("Geometry loop");
      geometry_method         = method();
      geometry_max_iterations = prm.get_integer("Maximum iterations");
      geometry_tolerance      = prm.get_double("Tolerance");
      prm.leave_subsection();
      prm.enter_subsection("Friction loop");
      friction_method         = method();
      friction_max_iterations = prm.get_integer("Maximum iterations");
      friction_tolerance      = prm.get_double("Tolerance");
      prm.leave_subsection();
      prm.enter_subsection("Status loop");
      status_method         = method();
      status_max_iterations = prm.get_integer("Maximum iterations");
      prm.leave_subsection();
      prm.enter_subsection("Newton");
      newton_max_iterations       = prm.get_integer("Maximum iterations");
      newton_tolerance            = prm.get_double("Tolerance");
      line_search_steps           = prm.get_integer("Line search steps");
      const std::string criterion = prm.get("Residual");
      newton_criterion            = criterion == "scaled"     ? ResidualCriterion::scaled
                                    : criterion == "absolute" ? ResidualCriterion::absolute
                                                              : ResidualCriterion::relative;
      prm.leave_subsection();
      prm.leave_subsection();
    }

    void
    LinearSolver::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      prm.declare_entry(
          "Method",
          "direct",
          Patterns::Selection("direct|iterative|automatic"),
          "automatic: iterative in 3D from `Automatic threshold` unknowns on, direct below it "
          "and in 2D (decided on each mesh). "
          "direct: one sparse factorisation per Newton system (`Direct solver`). iterative: "
          "GMRES with a block-triangular preconditioner, algebraic multigrid (Trilinos ML) on "
          "the displacement block and the Schur complement with the displacement block's "
          "diagonal on the multipliers (doc/formulation.md, \"Iterative linear solver\"); its "
          "tolerance follows the Newton residual (`Forcing term`), and a system it does not "
          "solve within `Maximum iterations` is solved by the direct solver instead.");
      prm.declare_entry("Automatic threshold",
                        "20000",
                        Patterns::Integer(1),
                        "Method = automatic: the unknowns (displacement and multipliers) of a 3D "
                        "mesh from which the iterative solver is used. Measured on the 3D Hertz "
                        "ball (doc/iterative_solver.md): 2.1 times faster per Newton iteration "
                        "than the direct solver at 26k DoFs, 12 times at 176k; below, both take "
                        "well under a second and the direct solver's exact solves are kept.");
      prm.declare_entry(
          "Forcing term",
          "Newton tolerance",
          Patterns::Selection("Newton tolerance|Eisenstat-Walker"),
          "Method = iterative: the relative GMRES tolerance of each Newton system. Newton "
          "tolerance: a tenth of the reduction of the Newton criterion's measure that would "
          "meet its tolerance in this iteration, so that a Newton loop whose statuses are "
          "frozen (a linear problem) ends in the iterations of the direct solver. "
          "Eisenstat-Walker: choice 2 of Eisenstat and Walker (1996), looser early in a "
          "loop; it costs Newton iterations on these problems (doc/iterative_solver.md). "
          "Both within [1e-10, Maximum forcing term].");
      prm.declare_entry(
          "Maximum forcing term",
          "1e-3",
          Patterns::Double(1e-14, 0.5),
          "Method = iterative: the largest relative GMRES tolerance |b - J x| / |b|.");
      prm.declare_entry(
          "Schur augmentation",
          "10",
          Patterns::Double(0., 1e6),
          "Method = iterative: c in the augmented preconditioner. The multiplier rows that "
          "only constrain the displacement, each on its own (no entry in D, no displacement DoF "
          "shared with another row: a nodal contact quadrature against a rigid obstacle) are "
          "added to the displacement rows, weighted by Gamma = c diag(C diag(K)^-1 C^T)^-1, so the "
          "multigrid "
          "works on K + C^T Gamma C (a penalty stiffness of c times the node's diagonal) and the "
          "Schur complement with diag(K + C^T Gamma C) is within a factor (1 + c) / c of the "
          "exact one whatever the mesh (doc/formulation.md, \"Iterative linear solver\"). "
          "0: no augmentation (K, and D - C diag(K)^-1 B, off by a factor that grows under "
          "refinement).");
      prm.declare_entry(
          "AMG near-null space",
          "translations",
          Patterns::Selection("translations|rigid body modes"),
          "Method = iterative: the modes the algebraic multigrid keeps on its coarse levels. "
          "rigid body modes adds the rotations: fewer GMRES iterations (3D Hertz ball at 176k "
          "DoFs: 22 instead of 30 per solve), a set-up twice as dear, about 1.2 times the "
          "time per Newton iteration on one rank (doc/iterative_solver.md). In an "
          "axisymmetric model the translations only.");
      prm.declare_entry("Maximum iterations",
                        "300",
                        Patterns::Integer(1, 100000),
                        "Method = iterative: GMRES iterations per Newton system.");
      prm.declare_entry("Direct solver",
                        "Amesos_Mumps",
                        Patterns::Selection("Amesos_Klu|Amesos_Mumps|Amesos_Superludist"),
                        "Trilinos Amesos sparse direct solver for each Newton system. "
                        "MUMPS is 2x (2D) to 8x (3D) faster than KLU on these saddle-point "
                        "systems (doc/benchmark_patin.md).");
      prm.declare_entry("Null pivot detection",
                        "false",
                        Patterns::Bool(),
                        "MUMPS only: detect null pivots and return one solution of a singular "
                        "system instead of failing. Pairs that violate the inf-sup condition "
                        "(Q1/P2) make the Newton system singular wherever contact is active; "
                        "with this their (non-unique) multipliers can be looked at.");
      prm.declare_entry("Work space increase",
                        "20",
                        Patterns::Integer(0, 100000),
                        "MUMPS only: percent added to the work space MUMPS estimates at the "
                        "analysis (its ICNTL(14)). Pivoting on the saddle-point systems can need "
                        "more than estimated: where the factorisation says the space is too small "
                        "(INFOG(1) = -8, -9, -11, -14, -15, -17, -20), it is redone with this "
                        "margin quadrupled, up to three times, before the run stops.");
      prm.declare_entry("Threads per rank",
                        "1",
                        Patterns::Integer(1, 256),
                        "BLAS and OpenMP threads of each MPI rank (the direct solver's dense "
                        "kernels). The program sets them itself, whatever OPENBLAS_NUM_THREADS "
                        "or OMP_NUM_THREADS say, so a run does not depend on the environment; "
                        "the command-line option --threads N overrides this entry. At most the "
                        "processors each rank has and as many as the address space left under "
                        "its limit (ulimit -v) holds OpenBLAS's 128 MiB thread buffers for are "
                        "used, with a note when fewer. Different "
                        "thread counts round differently: loop counts stay the same with the "
                        "scaled Newton criterion, values agree to round-off.");
      prm.leave_subsection();
    }

    void
    LinearSolver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      iterative            = prm.get("Method") == "iterative";
      automatic            = prm.get("Method") == "automatic";
      automatic_threshold  = prm.get_integer("Automatic threshold");
      eisenstat_walker     = prm.get("Forcing term") == "Eisenstat-Walker";
      maximum_forcing_term = prm.get_double("Maximum forcing term");
      maximum_iterations   = prm.get_integer("Maximum iterations");
      schur_augmentation   = prm.get_double("Schur augmentation");
      rigid_body_modes     = prm.get("AMG near-null space") == "rigid body modes";
      direct_solver        = prm.get("Direct solver");
      null_pivot_detection = prm.get_bool("Null pivot detection");
      threads_per_rank     = prm.get_integer("Threads per rank");
      workspace_increase   = prm.get_integer("Work space increase");
      if (null_pivot_detection && direct_solver != "Amesos_Mumps")
        throw InputError("Linear solver/Null pivot detection = true needs Direct solver = "
                         "Amesos_Mumps, got " +
                         direct_solver + ".");
      prm.leave_subsection();
    }

    void
    Output::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      prm.declare_entry(
          "Output directory", "output", Patterns::FileName(Patterns::FileName::output));
      prm.declare_entry(
          "Write vtu", "true", Patterns::Bool(), "Write .pvd/.vtu/.pvtu per load step.");
      prm.declare_entry("Write profiles",
                        "true",
                        Patterns::Bool(),
                        "Write a contact-surface profile .csv per load step.");
      prm.declare_entry("Checkpoint interval",
                        "0",
                        Patterns::Integer(0),
                        "Load steps between checkpoints (0: none). A checkpoint (directory "
                        "`checkpoint` in the output directory, replaced atomically) holds the "
                        "mesh with its refinements, the solution, the multipliers, the contact "
                        "points' states, the material history, the step controller and the "
                        "statistics; `stabilized_lagrangian --resume input.prm` continues from "
                        "it on the same number of MPI ranks. Between a resume and its "
                        "checkpoint only `Load stepping/End time` and `Wall time limit`, the "
                        "`Output` entries other than the directory and `Linear solver/Threads per "
                        "rank` may change.");
      prm.declare_entry("Log Newton iterations",
                        "false",
                        Patterns::Bool(),
                        "Print every Newton iterate's residual, the line search's step "
                        "lengths and the open/stick/slip counts of each trial: to see where "
                        "an algorithm spends its iterations.");
      prm.leave_subsection();
    }

    void
    AdaptiveRefinement::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Adaptive refinement");
      prm.declare_entry(
          "Cycles",
          "0",
          Patterns::Integer(0, 60),
          "Adaptive refinement: after the whole load path is solved, the mesh "
          "is refined by the `Criterion` and the load path is solved again from "
          "rest on the new mesh, this many times. The last mesh writes into the output "
          "directory, the earlier ones into cycle-N/ below it, and "
          "refinement_cycles.csv sums them up.");
      prm.declare_entry("Criterion",
                        "active set",
                        Patterns::Selection("active set|Kelly|estimator|uniform"),
                        "active set: refine the cells near the points in contact (below); "
                        "Kelly: refine the `Refined fraction` of the cells with the largest "
                        "Kelly indicators (jumps of the displacement gradient across faces), "
                        "which also follows the stresses below the contact zone; estimator: "
                        "the `Refined fraction` with the largest residual error indicators "
                        "eta_K of the last load step (the field error_indicator, with the "
                        "contact terms; doc/formulation.md, \"Error estimate\"); uniform: "
                        "every cell (nested meshes, for convergence studies).");
      prm.declare_entry("Refined fraction",
                        "0.3",
                        Patterns::Double(0., 1.),
                        "Kelly, estimator: with `Marking = fixed number`, the fraction of the "
                        "cells refined at each cycle; with `bulk`, the fraction of the sum of "
                        "the squared indicators that the refined cells carry.");
      prm.declare_entry("Marking",
                        "fixed number",
                        Patterns::Selection("fixed number|bulk"),
                        "Kelly, estimator: which cells the indicators refine. fixed number: "
                        "the `Refined fraction` of the cells with the largest indicators; "
                        "bulk: the fewest cells whose squared indicators make up the `Refined "
                        "fraction` of their sum (Doerfler marking, which the convergence of "
                        "adaptive finite elements rests on; it refines only where the error "
                        "concentrates, with smaller steps and more cycles: "
                        "doc/error_estimator.md).");
      prm.declare_entry("Errors against the last cycle",
                        "false",
                        Patterns::Bool(),
                        "Carry every cycle's displacement through the refinements (exactly: "
                        "the meshes are nested) and measure it against the last cycle's in "
                        "the energy norm of the last state's tangent; cycle_errors.csv gives "
                        "it beside the error estimate of that cycle and their ratio (the "
                        "effectivity index against this reference). Not with --resume.");
      prm.declare_entry("Target error",
                        "0",
                        Patterns::Double(0., 1.),
                        "Accuracy target: the cycles stop as soon as the estimated relative "
                        "error of the last load step in the energy norm "
                        "(estimated_relative_error) is at most this; `Cycles` is then the most "
                        "cycles. The output directory holds the cycle that met it (the earlier "
                        "ones in cycle-N/), target_error.csv what it cost. 0: no target.");
      prm.declare_entry("Target pressure error",
                        "0",
                        Patterns::Double(0., 1.),
                        "Accuracy target on the contact pressure: the estimated relative L2 "
                        "error of the pressure on the contact surface (estimated_pressure_error: "
                        "the mismatch between the multiplier and the pressure recovered from "
                        "the stress and, where the contact zone ends, from a square-root onset; "
                        "doc/formulation.md, \"Error estimate\"), as `Target error`; with "
                        "both, both must be met. 0: no target.");
      prm.declare_entry("Refinement band",
                        "0.5",
                        Patterns::Double(0.),
                        "active set: cells closer to a point in contact than this fraction of "
                        "the active zone's size (the diameter of its bounding box), plus half "
                        "their own diameter, are refined.");
      prm.leave_subsection();
    }

    void
    AdaptiveRefinement::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Adaptive refinement");
      cycles                                          = prm.get_integer("Cycles");
      const std::map<std::string, Criterion> criteria = {{"active set", Criterion::active_set},
                                                         {"Kelly", Criterion::kelly},
                                                         {"estimator", Criterion::estimator},
                                                         {"uniform", Criterion::uniform}};
      criterion                                       = criteria.at(prm.get("Criterion"));
      errors_against_last_cycle = prm.get_bool("Errors against the last cycle");
      target_error              = prm.get_double("Target error");
      target_pressure_error     = prm.get_double("Target pressure error");
      band                      = prm.get_double("Refinement band");
      fraction                  = prm.get_double("Refined fraction");
      bulk_marking              = prm.get("Marking") == "bulk";
      prm.leave_subsection();
      if (targeted() && cycles == 0)
        throw InputError("Adaptive refinement/Target error and Target pressure error need "
                         "`Cycles` > 0: the most refinement cycles the target may take.");
    }

    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      directory           = prm.get("Output directory");
      write_vtu           = prm.get_bool("Write vtu");
      write_profiles      = prm.get_bool("Write profiles");
      log_newton          = prm.get_bool("Log Newton iterations");
      checkpoint_interval = prm.get_integer("Checkpoint interval");
      prm.leave_subsection();
    }

    namespace
    {
      /** The condition subsections declare_all() declares as the template: `1` of each kind. */
      ConditionSections
      template_sections()
      {
        ConditionSections sections;
        for (const auto &kind : StabilizedLagrangian::BoundaryConditions::kinds())
          sections.conditions[kind] = {"1"};
        sections.zones = {"1"};
        return sections;
      }

      /**
       * The key ParameterHandler stores subsection @p name under: each
       * character outside [A-Za-z0-9] written as `_` and two hex digits. Its
       * subsections are in the order of their keys, the order in which the
       * conditions have always been applied and numbered.
       */
      std::string
      subsection_key(const std::string &name)
      {
        static const char *hex = "0123456789abcdef";
        std::string        key;
        for (const unsigned char c : name)
          if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))
            key += static_cast<char>(c);
          else
            key += std::string{'_', hex[c / 16], hex[c % 16]};
        return key;
      }

      /** The names of @p names and @p more, each once, in ParameterHandler's order. */
      std::vector<std::string>
      merged(std::vector<std::string> names, const std::vector<std::string> &more)
      {
        for (const auto &name : more)
          if (std::find(names.begin(), names.end(), name) == names.end())
            names.push_back(name);
        std::sort(names.begin(), names.end(), [](const auto &a, const auto &b) {
          return subsection_key(a) < subsection_key(b);
        });
        return names;
      }

      /** The sections of @p text and the template's, each once, in ParameterHandler's order. */
      ConditionSections
      with_template(const ConditionSections &text)
      {
        ConditionSections result = template_sections();
        for (const auto &[kind, names] : text.conditions)
          result.conditions[kind] = merged(result.conditions[kind], names);
        result.zones = merged(result.zones, text.zones);
        return result;
      }
    } // namespace

    template <int dim>
    void
    declare_all(ParameterHandler &prm)
    {
      prm.declare_entry("Dimension",
                        "2",
                        Patterns::Integer(2, 3),
                        "2 (plane strain, or axisymmetric: Geometry/Axisymmetric) or 3.");
      Geometry::declare_parameters<dim>(prm);
      Obstacles::declare_parameters<dim>(prm);
      prm.enter_subsection("Obstacle");
      prm.enter_subsection("Motion");
      declare_function<dim>(prm,
                            "mm: the obstacle's translation d at time t; 0: fixed; only t is used");
      prm.declare_entry("Rotation centre",
                        dim == 2 ? "0, 0" : "0, 0, 0",
                        Patterns::List(Patterns::Double(), dim, dim),
                        "The point c the obstacle turns about (mm), where it is at rest; it moves "
                        "with the translation d.");
      prm.enter_subsection("Rotation");
      declare_function<dim>(prm,
                            dim == 2 ? "rad: the angle the obstacle has turned by about its "
                                       "rotation centre at time t, counter-clockwise; only t "
                                       "is used"
                                     : "rad: the rotation vector (axis times angle) the "
                                       "obstacle has turned by about its rotation centre at "
                                       "time t; only t is used",
                            dim == 2 ? 1 : 3);
      prm.leave_subsection();
      prm.leave_subsection();
      prm.leave_subsection();
      Materials::declare_parameters<dim>(prm);
      Contact::declare_parameters(prm,
                                  Discretization::Registry<dim>::pattern(),
                                  Discretization::Registry<dim>::documentation(
                                      "Displacement / multiplier spaces (λ_n and Λ together):"));
      StabilizedLagrangian::BoundaryConditions::declare_parameters<dim>(prm, template_sections());
      declare_contact_zones(prm, template_sections().zones);
      LoadStepping::declare_parameters(prm);
      NonlinearSolver::declare_parameters(prm);
      LinearSolver::declare_parameters(prm);
      AdaptiveRefinement::declare_parameters(prm);
      Output::declare_parameters(prm);
    }

    namespace
    {
      /** A parameter file larger than this is not one (a device, a log, a mesh). */
      constexpr std::uintmax_t max_parameter_file_size = std::uintmax_t(16) << 20;
      /** Deeper include chains than this are refused (a cycle is caught before). */
      constexpr unsigned int max_include_depth = 32;

      /** A parameter file with its includes expanded, and where each line came from. */
      struct ExpandedFile
      {
        std::string                                   text;
        std::vector<std::pair<std::string, unsigned>> origin; // (file, line) of each line
      };

      /**
       * The content of the text file @p filename: refused with a message when it
       * is missing, a directory, a device, FIFO or socket (reading would block or
       * never end), larger than max_parameter_file_size, or binary.
       */
      std::string
      read_text_file(const std::string &filename, const std::string &what)
      {
        namespace fs = std::filesystem;
        std::error_code ec;
        const auto      status = fs::status(filename, ec);
        if (!fs::exists(status))
          throw InputError(what + " '" + filename + "' does not exist.");
        if (fs::is_directory(status))
          throw InputError(what + " '" + filename + "' is a directory, not a parameter file.");
        if (!fs::is_regular_file(status))
          throw InputError(what + " '" + filename +
                           "' is not a regular file (a device, FIFO or socket): give a "
                           "parameter file.");
        if (fs::file_size(filename, ec) > max_parameter_file_size)
          throw InputError(what + " '" + filename + "' is larger than " +
                           std::to_string(max_parameter_file_size >> 20) +
                           " MiB: not a parameter file.");
        std::ifstream file(filename, std::ios::binary);
        if (!file)
          throw InputError("Cannot open " + what + " '" + filename + "' (permissions?).");
        std::stringstream content;
        content << file.rdbuf();
        const std::string text = content.str();
        if (text.find('\0') != std::string::npos)
          throw InputError(what + " '" + filename +
                           "' contains NUL bytes: a binary file, not a parameter file.");
        return text;
      }

      /** The file named by an `include` (or `INCLUDE`) line, or nothing. */
      std::optional<std::string>
      included_file(const std::string &line)
      {
        std::string statement = line.substr(0, line.find('#'));
        statement             = Utilities::trim(statement);
        for (const std::string keyword : {"include", "INCLUDE"})
          if (statement.rfind(keyword, 0) == 0 &&
              (statement.size() == keyword.size() ||
               std::isspace(static_cast<unsigned char>(statement[keyword.size()]))))
            return Utilities::trim(statement.substr(keyword.size()));
        return std::nullopt;
      }

      /**
       * Expand the `include` lines of @p filename recursively (each included
       * file as given if it exists, else beside the including file), refusing a
       * file that includes itself, directly or not, and chains deeper than
       * max_include_depth.
       */
      void
      expand(const std::string &filename, std::vector<std::string> &chain, ExpandedFile &out)
      {
        namespace fs           = std::filesystem;
        const std::string what = chain.empty() ? "The parameter file" : "The included file";
        const std::string text = read_text_file(filename, what);
        std::error_code   ec;
        const std::string canonical = fs::weakly_canonical(filename, ec).string();
        if (std::find(chain.begin(), chain.end(), canonical) != chain.end())
          {
            std::string cycle;
            for (const auto &file : chain)
              cycle += file + " -> ";
            throw InputError("The parameter file includes itself: " + cycle + canonical + ".");
          }
        if (chain.size() >= max_include_depth)
          throw InputError("More than " + std::to_string(max_include_depth) +
                           " nested include statements, at '" + filename + "'.");
        chain.push_back(canonical);
        std::istringstream lines(text);
        std::string        line;
        for (unsigned int number = 1; std::getline(lines, line); ++number)
          if (const auto include = included_file(line))
            {
              if (include->empty())
                throw InputError("'" + filename + "' line " + std::to_string(number) +
                                 ": an include statement without a file name.");
              std::string path = *include;
              if (!fs::path(path).is_absolute() && !fs::exists(path))
                path = (fs::path(filename).parent_path() / path).string();
              expand(path, chain, out);
            }
          else
            {
              out.text += line + "\n";
              out.origin.emplace_back(filename, number);
            }
        chain.pop_back();
      }

      /** The parameter file @p filename expanded; refused if it sets no parameter. */
      ExpandedFile
      read_file(const std::string &filename)
      {
        ExpandedFile             result;
        std::vector<std::string> chain;
        expand(filename, chain, result);
        if (!std::regex_search(result.text, std::regex("(^|\n)[ \t]*set[ \t]")))
          throw InputError("The parameter file '" + filename +
                           "' sets no parameter (an empty file?). Run the program without a "
                           "file for the built-in scene.");
        return result;
      }

      /**
       * ParameterHandler's message with "Line <N> of file <input string>"
       * replaced by the file and line the expanded line N came from.
       */
      std::string
      locate(const std::string &message, const ExpandedFile &file)
      {
        static const std::regex where("Line <([0-9]+)> of file <[^>]*>");
        std::smatch             match;
        if (!std::regex_search(message, match, where))
          return message;
        const unsigned long line = std::stoul(match[1]);
        if (line < 1 || line > file.origin.size())
          return message;
        const auto &[name, number] = file.origin[line - 1];
        return match.prefix().str() + "'" + name + "' line " + std::to_string(number) +
               match.suffix().str();
      }
    } // namespace

    namespace
    {
      std::string parameter_file_directory = ".";
    }

    std::string
    input_path(const std::string &path)
    {
      if (path.empty() || std::filesystem::path(path).is_absolute() ||
          std::filesystem::exists(path))
        return path;
      return (std::filesystem::path(parameter_file_directory) / path).string();
    }

    template <int dim>
    ConditionSections
    parse(ParameterHandler &prm, const std::string &text, const bool is_file)
    {
      if (is_file)
        parameter_file_directory = std::filesystem::path(text).parent_path().string();
      if (parameter_file_directory.empty())
        parameter_file_directory = ".";
      const ExpandedFile      content  = is_file ? read_file(text) : ExpandedFile{text, {}};
      const ConditionSections sections = condition_sections(content.text);
      StabilizedLagrangian::BoundaryConditions::declare_parameters<dim>(prm, sections);
      declare_contact_zones(prm, sections.zones);
      try
        {
          prm.parse_input_from_string(content.text);
        }
      catch (const ExceptionBase &e)
        {
          std::ostringstream message;
          e.print_info(message);
          throw InputError("Error in the parameter file " +
                           (is_file ? "'" + text + "'" : std::string("(built-in)")) + ":\n" +
                           locate(message.str(), content));
        }
      return with_template(sections);
    }

    unsigned int
    read_dimension(const std::string &text, const bool is_file)
    {
      ParameterHandler prm;
      prm.declare_entry("Dimension",
                        "2",
                        Patterns::Integer(2, 3),
                        "2 (plane strain, or axisymmetric: Geometry/Axisymmetric) or 3.");
      const ExpandedFile content = is_file ? read_file(text) : ExpandedFile{text, {}};
      try
        {
          prm.parse_input_from_string(content.text, "", true);
        }
      catch (const ExceptionBase &e)
        {
          std::ostringstream message;
          e.print_info(message);
          throw InputError("Error in the parameter file '" + text +
                           "': " + locate(message.str(), content));
        }
      return prm.get_integer("Dimension");
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
    template ConditionSections
    parse<2>(ParameterHandler &, const std::string &, const bool);
    template ConditionSections
    parse<3>(ParameterHandler &, const std::string &, const bool);
    template void
    declare_all<2>(ParameterHandler &);
    template void
    declare_all<3>(ParameterHandler &);
  } // namespace Parameters
} // namespace StabilizedLagrangian
