#include <deal.II/dofs/dof_tools.h>

#include <deal.II/numerics/vector_tools.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>

#include <cmath>

namespace StabilizedLagrangian
{
  namespace BoundaryConditions
  {
    namespace
    {
      /** The components a `Components` entry names. */
      template <int dim>
      ComponentMask
      parse_components(const ParameterHandler &prm)
      {
        std::vector<bool> mask(dim, false);
        for (const auto &c : Utilities::split_string_list(prm.get("Components")))
          mask[c == "x" ? 0 : (c == "y" ? 1 : 2)] = true;
        return ComponentMask(mask);
      }

      /** The largest change of @p displacement at @p x in @p components over a load step. */
      template <int dim>
      double
      largest_step_change(Parameters::BoundaryFunction<dim> &displacement,
                          const ComponentMask               &components,
                          const Point<dim>                  &x,
                          const LoadSteps                   &steps)
      {
        // The body starts undeformed (u = 0), so the first step's increment is
        // the value at the end of that step, whatever the function gives at t = 0.
        Vector<double> before(dim), after(dim);
        double         increment = 0.;
        for (unsigned int k = 0; k < steps.n_steps; ++k)
          {
            before = 0.;
            if (k > 0)
              {
                displacement.set_time(k * steps.step);
                displacement.vector_value(x, before);
              }
            displacement.set_time((k + 1) * steps.step);
            displacement.vector_value(x, after);
            double norm_squared = 0.;
            for (unsigned int d = 0; d < dim; ++d)
              if (components[d])
                norm_squared += Utilities::fixed_power<2>(after[d] - before[d]);
            increment = std::max(increment, std::sqrt(norm_squared));
          }
        return increment;
      }

      /** The components held by @p components, as Support::held. */
      template <int dim>
      std::vector<bool>
      held(const ComponentMask &components)
      {
        std::vector<bool> result(dim);
        for (unsigned int d = 0; d < dim; ++d)
          result[d] = components[d];
        return result;
      }
    } // namespace

    /** @brief A prescribed displacement on some components of a boundary. */
    template <int dim> class Dirichlet : public OnBoundary<dim>
    {
    public:
      Dirichlet(ParameterHandler &prm, const std::string &section)
          : OnBoundary<dim>(prm, section, OnBoundary<dim>::Role::support)
          , components(parse_components<dim>(prm))
          , displacement(Parameters::parse_function<dim>(prm, section, "Displacement"))
      {
      }

      void
      add_homogeneous_constraints(const Problem<dim>        &problem,
                                  AffineConstraints<double> &constraints) const override
      {
        VectorTools::interpolate_boundary_values(problem.dof_handler,
                                                 this->boundary_id,
                                                 Functions::ZeroFunction<dim>(dim),
                                                 constraints,
                                                 components);
      }

      void
      add_prescribed_values(const Problem<dim>                        &problem,
                            const double                               t,
                            std::map<types::global_dof_index, double> &values) const override
      {
        displacement->set_time(t);
        VectorTools::interpolate_boundary_values(
            problem.dof_handler, this->boundary_id, *displacement, values, components);
        displacement->check_finite(problem.communicator);
      }

      double
      largest_increment(const Problem<dim> &problem, const LoadSteps &steps) const override
      {
        double increment = 0.;
        for_each_boundary_vertex(
            problem.dof_handler.get_triangulation(),
            this->boundary_id,
            [&](const Point<dim> &vertex) {
              increment = std::max(increment,
                                   largest_step_change(*displacement, components, vertex, steps));
            });
        displacement->check_finite(problem.communicator);
        return increment;
      }

      void
      warn_if_not_ramped(const Problem<dim> &problem, const ConditionalOStream &out) const override
      {
        // A prescribed displacement that is not zero at t = 0 is applied whole in
        // the first load step, and cutting that step does not make it smaller.
        Vector<double> value(dim);
        double         largest = 0.;
        displacement->set_time(0.);
        for_each_boundary_vertex(problem.dof_handler.get_triangulation(),
                                 this->boundary_id,
                                 [&](const Point<dim> &vertex) {
                                   // (not noted as a failure: the run never evaluates t = 0)
                                   displacement->Functions::ParsedFunction<dim>::vector_value(
                                       vertex, value);
                                   for (unsigned int d = 0; d < dim; ++d)
                                     if (components[d] && std::isfinite(value[d]))
                                       largest = std::max(largest, std::abs(value[d]));
                                 });
        largest = Utilities::MPI::max(largest, problem.communicator);
        if (largest > 0.)
          out << "WARNING: " << displacement->name()
              << ": the prescribed displacement is not zero at t = 0 (up to " << largest
              << " mm); the body starts undeformed, so the first load step applies it at "
                 "once, and cutting that step does not reduce it. Make it grow from zero "
                 "with t (e.g. multiply it by t / End time) to spread it over the steps.\n";
      }

      void
      add_reactions(const Problem<dim>                    &problem,
                    const ReactionInputs<dim>             &inputs,
                    const std::vector<types::boundary_id> &ids,
                    std::vector<Tensor<1, dim>>           &reactions,
                    IndexSet                              &claimed) const override
      {
        // the residual without constraints on its DoFs, each counted once
        const unsigned int b = std::find(ids.begin(), ids.end(), this->boundary_id) - ids.begin();
        for (unsigned int c = 0; c < dim; ++c)
          if (components[c])
            {
              IndexSet dofs = boundary_component_dofs(problem.dof_handler, this->boundary_id, c);
              dofs          = dofs & problem.locally_owned_u;
              dofs.subtract_set(claimed);
              claimed.add_indices(dofs);
              for (const auto i : dofs)
                reactions[b][c] += inputs.internal_force(i) - inputs.external_force(i) +
                                   inputs.contact_residual(i);
            }
      }

      void
      add_supports(std::vector<Support<dim>> &supports) const override
      {
        supports.push_back(Support<dim>{this->boundary_id, Point<dim>(), held<dim>(components)});
      }

      void
      hold_components(const types::boundary_id id, std::vector<bool> &free) const override
      {
        if (id == this->boundary_id)
          for (unsigned int d = 0; d < dim; ++d)
            free[d] = free[d] && !components[d];
      }

      std::optional<IndexSet>
      prescribed_boundary_dofs(const Problem<dim> &problem, const unsigned int c) const override
      {
        if (!components[c])
          return std::nullopt;
        return boundary_component_dofs(problem.dof_handler, this->boundary_id, c);
      }

    private:
      const ComponentMask                                      components;
      const std::shared_ptr<Parameters::BoundaryFunction<dim>> displacement; ///< mm
    };

    /**
     * @brief A prescribed displacement on some components of one node of the
     * mesh, the vertex at a given point (`Dirichlet <name>` with `Point`).
     */
    template <int dim> class PointDirichlet : public Interface<dim>
    {
    public:
      PointDirichlet(const Point<dim> &point, ParameterHandler &prm, const std::string &section)
          : Interface<dim>(section)
          , point(point)
          , components(parse_components<dim>(prm))
          , displacement(Parameters::parse_function<dim>(prm, section, "Displacement"))
      {
      }

      bool
      at_one_vertex() const override
      {
        return true;
      }

      void
      find_dofs(const Problem<dim> &, const VertexDoFs<dim> &vertex_dofs) override
      {
        dofs = vertex_dofs(point, this->section());
      }

      void
      add_homogeneous_constraints(const Problem<dim> &,
                                  AffineConstraints<double> &constraints) const override
      {
        for (unsigned int c = 0; c < dim; ++c)
          if (components[c] && constraints.can_store_line(dofs[c]) &&
              !constraints.is_constrained(dofs[c]))
            constraints.add_line(dofs[c]);
      }

      void
      add_prescribed_values(const Problem<dim>                        &problem,
                            const double                               t,
                            std::map<types::global_dof_index, double> &values) const override
      {
        Vector<double> at_point(dim);
        displacement->set_time(t);
        displacement->vector_value(point, at_point);
        for (unsigned int c = 0; c < dim; ++c)
          if (components[c])
            values[dofs[c]] = at_point(c);
        displacement->check_finite(problem.communicator);
      }

      double
      largest_increment(const Problem<dim> &problem, const LoadSteps &steps) const override
      {
        const double increment = largest_step_change(*displacement, components, point, steps);
        displacement->check_finite(problem.communicator);
        return increment;
      }

      void
      add_supports(std::vector<Support<dim>> &supports) const override
      {
        supports.push_back(Support<dim>{std::nullopt, point, held<dim>(components)});
      }

      void
      add_statistics_columns(StatisticsWriter::Supports &supports) const override
      {
        supports.reaction_points.push_back(name());
      }

      void
      add_statistics(const Problem<dim>        &problem,
                     const ReactionInputs<dim> &inputs,
                     StepStatistics            &stats) const override
      {
        // the residual without constraints at its vertex
        std::array<double, 3> reaction = {{0., 0., 0.}};
        for (unsigned int c = 0; c < dim; ++c)
          if (components[c])
            {
              const types::global_dof_index i     = dofs[c];
              const bool                    owned = problem.locally_owned_u.is_element(i);
              reaction[c] =
                  Utilities::MPI::sum(owned ? inputs.internal_force(i) - inputs.external_force(i) +
                                                  inputs.contact_residual(i)
                                            : 0.,
                                      problem.communicator);
            }
        stats.point_reactions.push_back(reaction);
      }

      std::optional<types::global_dof_index>
      prescribed_point_dof(const unsigned int c) const override
      {
        if (!components[c])
          return std::nullopt;
        return dofs[c];
      }

    private:
      /** the subsection's name, for the columns: `Dirichlet <name>` */
      std::string
      name() const
      {
        return this->section().substr(std::string("Boundary conditions/Dirichlet ").size());
      }

      const Point<dim>                                         point; ///< a vertex of the mesh (mm)
      const ComponentMask                                      components;
      const std::shared_ptr<Parameters::BoundaryFunction<dim>> displacement; ///< mm
      std::array<types::global_dof_index, dim>                 dofs;         ///< the vertex's
    };

    namespace
    {
      template <int dim>
      void
      declare_dirichlet(ParameterHandler &prm)
      {
        OnBoundary<dim>::declare_boundary(prm, "with a prescribed displacement");
        prm.declare_entry("Point",
                          "",
                          Patterns::Anything(),
                          "Instead of a boundary: the coordinates (mm) of one vertex of the "
                          "mesh whose displacement is prescribed (for instance one node held "
                          "vertically); Boundary id stays -1. Empty: the boundary.");
        prm.declare_entry("Components",
                          dim == 2 ? "x, y" : "x, y, z",
                          Patterns::MultipleSelection(dim == 2 ? "x|y" : "x|y|z"),
                          "Displacement components that are prescribed.");
        prm.enter_subsection("Displacement");
        Parameters::declare_function<dim>(prm, "mm");
        prm.leave_subsection();
      }

      /** `Dirichlet <name>`: on a boundary, or with a `Point` at one vertex, or unused. */
      template <int dim>
      std::unique_ptr<Interface<dim>>
      create_dirichlet(ParameterHandler &prm, const std::string &section)
      {
        const bool on_boundary =
            OnBoundary<dim>(prm, section, OnBoundary<dim>::Role::support).used();
        const auto point = parse_point<dim>(prm, section);
        if (on_boundary && point)
          throw InputError(section +
                           ": both Boundary id and Point are given; a condition holds on a "
                           "boundary (Point empty) or at one node (Boundary id = -1).");
        if (on_boundary)
          return std::make_unique<Dirichlet<dim>>(prm, section);
        if (point)
          return std::make_unique<PointDirichlet<dim>>(*point, prm, section);
        return nullptr;
      }

      template <int dim>
      bool
      register_dirichlet()
      {
        Registry<dim>::add("Dirichlet",
                           "prescribed displacement",
                           &declare_dirichlet<dim>,
                           &create_dirichlet<dim>);
        return true;
      }

      [[maybe_unused]] const bool registered = register_dirichlet<2>() && register_dirichlet<3>();
    } // namespace
  }   // namespace BoundaryConditions
} // namespace StabilizedLagrangian
