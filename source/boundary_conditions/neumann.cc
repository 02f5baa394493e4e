#include <stabilized_lagrangian/boundary_conditions/interface.h>

namespace StabilizedLagrangian
{
  namespace BoundaryConditions
  {
    /** @brief A prescribed traction t(x, t) (MPa) on a boundary, in the reference configuration. */
    template <int dim> class Neumann : public OnBoundary<dim>
    {
    public:
      Neumann(ParameterHandler &prm, const std::string &section)
          : OnBoundary<dim>(prm, section, OnBoundary<dim>::Role::load)
          , traction(this->used() ? Parameters::parse_function<dim>(prm, section, "Traction")
                                  : nullptr)
      {
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        OnBoundary<dim>::declare_boundary(
            prm, "with a prescribed traction (MPa, in the reference configuration)");
        prm.enter_subsection("Traction");
        Parameters::declare_function<dim>(prm, "MPa");
        prm.leave_subsection();
      }

      void
      assemble_face(const Problem<dim> &problem, const FaceSystem<dim> &face) const override
      {
        // the work −∫ t·φ_i of the traction
        FEFaceValues<dim> &face_values = face.face_values;
        face_values.reinit(face.cell, face.face_no);
        traction->set_time(problem.time);
        Vector<double> t(dim);
        for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
          {
            const Point<dim> &x = face_values.quadrature_point(q);
            traction->vector_value(x, t);
            for (unsigned int i = 0; i < problem.fe.n_dofs_per_cell(); ++i)
              face.cell_rhs(i) -= t(problem.fe.system_to_component_index(i).first) *
                                  face_values.shape_value(i, q) * face_values.JxW(q) *
                                  problem.radial_weight(x);
          }
      }

      void
      check_finite(const MPI_Comm communicator) const override
      {
        traction->check_finite(communicator);
      }

      void
      add_boundary_load(const Problem<dim>      &problem,
                        const types::boundary_id id,
                        const Point<dim>        &x,
                        const Tensor<1, dim> &,
                        Vector<double> &load) const override
      {
        if (id != this->boundary_id)
          return;
        Vector<double> prescribed(dim);
        traction->set_time(problem.time);
        traction->vector_value(x, prescribed);
        load += prescribed;
      }

    private:
      const std::shared_ptr<Parameters::BoundaryFunction<dim>> traction;
    };

    SL_REGISTER_BOUNDARY_CONDITION(Neumann, "Neumann", "prescribed traction");
  } // namespace BoundaryConditions
} // namespace StabilizedLagrangian
