#include <stabilized_lagrangian/boundary_conditions/interface.h>

namespace StabilizedLagrangian
{
  namespace BoundaryConditions
  {
    /**
     * @brief An elastic support (a Robin condition): the traction
     * t = −K (u − u_0) on a boundary, K diagonal in the global axes.
     */
    template <int dim> class Spring : public OnBoundary<dim>
    {
    public:
      Spring(ParameterHandler &prm, const std::string &section)
          : OnBoundary<dim>(prm, section, OnBoundary<dim>::Role::elastic_support)
      {
        if (!this->used())
          return;
        const auto values =
            Utilities::string_to_double(Utilities::split_string_list(prm.get("Stiffness")));
        for (unsigned int d = 0; d < dim; ++d)
          stiffness[d] = values[d];
        if (stiffness.norm() == 0.)
          throw InputError(section + "/Stiffness: all zero, so the springs hold nothing; give a "
                                     "stiffness > 0 (MPa/mm) in at least one axis, or set Boundary "
                                     "id = -1.");
        reference = Parameters::parse_function<dim>(prm, section, "Reference displacement");
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        OnBoundary<dim>::declare_boundary(
            prm, "held by springs: the traction -K (u - u_0), per unit reference area");
        prm.declare_entry("Stiffness",
                          dim == 2 ? "0, 0" : "0, 0, 0",
                          Patterns::List(Patterns::Double(0.), dim, dim),
                          "K_xx, K_yy" + std::string(dim == 3 ? ", K_zz" : "") +
                              " (MPa/mm: traction per displacement, >= 0), along the "
                              "global axes; 0: that component is free.");
        prm.enter_subsection("Reference displacement");
        Parameters::declare_function<dim>(prm, "mm");
        prm.leave_subsection();
      }

      void
      assemble_face(const Problem<dim> &problem, const FaceSystem<dim> &face) const override
      {
        // the traction t = −K (u − u_0): its work −∫ t·φ_i in the residual and
        // ∫ K φ_i φ_j (same component) in the Jacobian
        const FiniteElement<dim> &fe          = problem.fe;
        FEFaceValues<dim>        &face_values = face.face_values;
        face_values.reinit(face.cell, face.face_no);
        reference->set_time(problem.time);
        const unsigned int n_dofs = fe.n_dofs_per_cell();
        Vector<double>     u_0(dim);
        for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
          {
            reference->vector_value(face_values.quadrature_point(q), u_0);
            Tensor<1, dim> u;
            for (unsigned int j = 0; j < n_dofs; ++j)
              u[fe.system_to_component_index(j).first] +=
                  face.coefficients[j] * face_values.shape_value(j, q);
            const double JxW =
                face_values.JxW(q) * problem.radial_weight(face_values.quadrature_point(q));
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                const unsigned int c = fe.system_to_component_index(i).first;
                if (stiffness[c] == 0.)
                  continue;
                const double k_phi = stiffness[c] * face_values.shape_value(i, q) * JxW;
                face.cell_rhs(i) += k_phi * (u[c] - u_0(c));
                if (face.assemble_matrix)
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    if (fe.system_to_component_index(j).first == c)
                      face.cell_matrix(i, j) += k_phi * face_values.shape_value(j, q);
              }
          }
      }

      void
      check_finite(const MPI_Comm communicator) const override
      {
        reference->check_finite(communicator);
      }

      void
      add_reactions(const Problem<dim>                    &problem,
                    const ReactionInputs<dim>             &inputs,
                    const std::vector<types::boundary_id> &ids,
                    std::vector<Tensor<1, dim>>           &reactions,
                    IndexSet &) const override
      {
        // the springs' force on the body, ∫ −K (u − u_0)
        const TrilinosWrappers::MPI::Vector &u = inputs.displacement();
        FEFaceValues<dim>                    face_values(problem.fe,
                                      inputs.face_quadrature,
                                      update_values | update_quadrature_points | update_JxW_values);
        std::vector<Tensor<1, dim>>          values(face_values.n_quadrature_points);
        Vector<double>                       u_0(dim);
        reference->set_time(problem.time);
        const unsigned int b = std::find(ids.begin(), ids.end(), this->boundary_id) - ids.begin();
        for (const auto &cell : problem.dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == this->boundary_id)
                {
                  face_values.reinit(cell, f);
                  face_values[FEValuesExtractors::Vector(0)].get_function_values(u, values);
                  for (unsigned int q = 0; q < values.size(); ++q)
                    {
                      const Point<dim> &x = face_values.quadrature_point(q);
                      reference->vector_value(x, u_0);
                      for (unsigned int d = 0; d < dim; ++d)
                        reactions[b][d] -= stiffness[d] * (values[q][d] - u_0(d)) *
                                           face_values.JxW(q) * problem.radial_weight(x);
                    }
                }
      }

      void
      add_supports(std::vector<Support<dim>> &supports) const override
      {
        std::vector<bool> held(dim);
        for (unsigned int d = 0; d < dim; ++d)
          held[d] = stiffness[d] > 0.;
        supports.push_back(Support<dim>{this->boundary_id, Point<dim>(), held});
      }

      void
      add_boundary_load(const Problem<dim>      &problem,
                        const types::boundary_id id,
                        const Point<dim>        &x,
                        const Tensor<1, dim>    &u,
                        Vector<double>          &load) const override
      {
        // a spring's traction −K (u_h − u_0)
        if (id != this->boundary_id)
          return;
        Vector<double> u_0(dim);
        reference->set_time(problem.time);
        reference->vector_value(x, u_0);
        for (unsigned int d = 0; d < dim; ++d)
          load(d) -= stiffness[d] * (u[d] - u_0(d));
      }

    private:
      Tensor<1, dim> stiffness; ///< K_xx, K_yy (, K_zz), MPa/mm: traction per displacement
      std::shared_ptr<Parameters::BoundaryFunction<dim>> reference; ///< u_0(x, t), mm
    };

    SL_REGISTER_BOUNDARY_CONDITION(Spring, "Spring", "elastic support");
  } // namespace BoundaryConditions
} // namespace StabilizedLagrangian
