#include <stabilized_lagrangian/boundary_conditions/interface.h>

namespace StabilizedLagrangian
{
  namespace BoundaryConditions
  {
    /** @brief A force F(t) on one node of the mesh, the vertex at a given point. */
    template <int dim> class PointLoad : public Interface<dim>
    {
    public:
      PointLoad(ParameterHandler &prm, const std::string &section)
          : Interface<dim>(section)
          , point(parse_point<dim>(prm, section))
          , force(point ? Parameters::parse_function<dim>(prm, section, "Force") : nullptr)
      {
      }

      /** @brief False where `Point` is empty. */
      bool
      used() const override
      {
        return point.has_value();
      }

      /**
       * @brief It acts at one vertex: after the conditions on boundaries, so
       * its force is added after their global terms (a rigid plate's on its
       * reference DoFs).
       */
      bool
      at_one_vertex() const override
      {
        return true;
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Point",
                          "",
                          Patterns::Anything(),
                          "Where the force acts: the coordinates of a vertex of the mesh "
                          "(mm); empty: unused.");
        prm.enter_subsection("Force");
        Parameters::declare_function<dim>(prm, "N, per mm of thickness in 2D; only t is used");
        prm.leave_subsection();
      }

      void
      find_dofs(const Problem<dim> &, const VertexDoFs<dim> &vertex_dofs) override
      {
        dofs = vertex_dofs(*point, this->section());
      }

      void
      assemble_global(const Problem<dim>              &problem,
                      const AffineConstraints<double> &constraints,
                      TrilinosWrappers::MPI::Vector   &system_rhs,
                      TrilinosWrappers::MPI::Vector   &external_force) const override
      {
        // the force at its vertex's DoFs, through the constraints (a
        // prescribed component takes the load into its reaction, a plate's
        // tied one passes it to the plate)
        const Vector<double> value = value_at_time(*force, problem.time);
        force->check_finite(problem.communicator);
        if (!problem.locally_owned.is_element(dofs[0]))
          return;
        const std::vector<types::global_dof_index> vertex(dofs.begin(), dofs.end());
        Vector<double>                             load_rhs(dim);
        for (unsigned int c = 0; c < dim; ++c)
          load_rhs(c) = -value(c);
        constraints.distribute_local_to_global(load_rhs, vertex, system_rhs);
        for (unsigned int c = 0; c < dim; ++c)
          external_force(vertex[c]) += value(c);
      }

      void
      warn_if_held(const Problem<dim>              &problem,
                   const AffineConstraints<double> &constraints,
                   const double                     end_time,
                   const ConditionalOStream        &out) const override
      {
        // A component a Dirichlet condition holds (constrained to a value,
        // with no entries: not a hanging node's nor a plate's tie) takes the
        // force into its reaction: the body never feels it.
        unsigned int held = 0;
        if (problem.locally_owned.is_element(dofs[0]))
          for (unsigned int k = 0; k <= 20; ++k)
            {
              const Vector<double> value = value_at_time(*force, k / 20. * end_time);
              for (unsigned int c = 0; c < dim; ++c)
                if (value(c) != 0. && constraints.is_constrained(dofs[c]) &&
                    constraints.get_constraint_entries(dofs[c])->empty())
                  held |= 1u << c;
            }
        held = Utilities::MPI::max(held, problem.communicator);
        if (held == 0)
          return;
        std::string components;
        for (unsigned int c = 0; c < dim; ++c)
          if (held & (1u << c))
            components += std::string(components.empty() ? "" : ", ") + "xyz"[c];
        out << "WARNING: " << this->section() << ": a Dirichlet condition holds its vertex in "
            << components
            << ": that part of the force goes into the support's reaction and does not load "
               "the body. Move the Point, or the load to a vertex the supports leave free.\n";
      }

    private:
      const std::optional<Point<dim>>                          point; ///< a vertex of the mesh (mm)
      const std::shared_ptr<Parameters::BoundaryFunction<dim>> force; ///< N (N/mm in 2D)
      std::array<types::global_dof_index, dim>                 dofs;  ///< the vertex's
    };

    SL_REGISTER_BOUNDARY_CONDITION(PointLoad, "Point load", "a force on one vertex");
  } // namespace BoundaryConditions
} // namespace StabilizedLagrangian
