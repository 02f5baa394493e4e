// A boundary condition kind added from outside source/ (issue 44, item 2):
// one class and its registration. `Toy traction <name>`, a constant traction
// on a boundary, must give the same solution as the `Neumann <name>` condition
// with the same traction: the problem asks each condition for its part and
// never which kind it is.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include "check_tools.h"

#include <filesystem>
#include <string>

using namespace dealii;
using namespace StabilizedLagrangian;

namespace
{
  /** @brief A traction t, constant in space and time, on a boundary. */
  template <int dim> class ToyTraction : public BoundaryConditions::OnBoundary<dim>
  {
  public:
    ToyTraction(ParameterHandler &prm, const std::string &section)
        : BoundaryConditions::OnBoundary<dim>(
              prm, section, BoundaryConditions::OnBoundary<dim>::Role::load)
    {
      const auto values =
          Utilities::string_to_double(Utilities::split_string_list(prm.get("Traction")));
      for (unsigned int d = 0; d < dim; ++d)
        traction[d] = values[d];
    }

    static void
    declare_parameters(ParameterHandler &prm)
    {
      BoundaryConditions::OnBoundary<dim>::declare_boundary(prm, "with a constant traction");
      prm.declare_entry("Traction",
                        dim == 2 ? "0, 0" : "0, 0, 0",
                        Patterns::List(Patterns::Double(), dim, dim),
                        "t (MPa).");
    }

    void
    assemble_face(const BoundaryConditions::Problem<dim>    &problem,
                  const BoundaryConditions::FaceSystem<dim> &face) const override
    {
      // the work −∫ t·φ_i of the traction
      FEFaceValues<dim> &face_values = face.face_values;
      face_values.reinit(face.cell, face.face_no);
      for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
        for (unsigned int i = 0; i < problem.fe.n_dofs_per_cell(); ++i)
          face.cell_rhs(i) -= traction[problem.fe.system_to_component_index(i).first] *
                              face_values.shape_value(i, q) * face_values.JxW(q) *
                              problem.radial_weight(face_values.quadrature_point(q));
    }

  private:
    Tensor<1, dim> traction;
  };

  SL_REGISTER_BOUNDARY_CONDITION(ToyTraction, "Toy traction", "a constant traction");

  /** The elastic patin (prm/patin_elastic.prm), coarse, pushed on its right side by @p push. */
  std::string
  scene(const std::string &push)
  {
    return CheckTools::coarse_patin(SL_PRM_DIR) + R"(
subsection Load stepping
  set Number of load steps = 2
end
subsection Boundary conditions
)" + push + R"(
end
subsection Output
  set Output directory = boundary_condition_plugin_output
  set Write vtu        = false
  set Write profiles   = false
end
)";
  }

  /** The solution at the end of the load path of the scene with @p push (named @p name). */
  TrilinosWrappers::MPI::Vector
  solve(const std::string &name, const std::string &push)
  {
    ParameterHandler prm;
    Parameters::declare_all<2>(prm);
    const auto        sections = Parameters::parse<2>(prm, scene(push), false);
    ContactProblem<2> problem(prm, sections, false);
    CheckTools::check(problem.run(), "the run " + name + " ends", 0.);
    return problem.current_solution();
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::filesystem::remove_all("boundary_condition_plugin_output");

  TrilinosWrappers::MPI::Vector       free = solve("without a push", "");
  const TrilinosWrappers::MPI::Vector neumann =
      solve("with the Neumann condition", R"(  subsection Neumann side
    set Boundary id = 1
    subsection Traction
      set Function expression = -20; 5
    end
  end)");
  TrilinosWrappers::MPI::Vector toy = solve("with the toy kind", R"(  subsection Toy traction side
    set Boundary id = 1
    set Traction    = -20, 5
  end)");
  free -= neumann;
  CheckTools::check(
      free.l2_norm() > 1e-6 * neumann.l2_norm(), "the push changes the solution", free.l2_norm());
  toy -= neumann;
  CheckTools::check_below(toy.l2_norm(),
                          1e-12 * neumann.l2_norm(),
                          "the toy kind's solution is the Neumann condition's");
  return CheckTools::summary();
}
