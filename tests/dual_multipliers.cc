// The dual (biorthogonal) multiplier basis of the pairs `Q1/P1 dual` and
// `Q2/P2 dual` (doc/formulation.md, "Dual multipliers"): the multiplier mass
// matrix M_jk = ∫_Γc ψ_j φ_k is diagonal with D_jj = ∫_Γc φ_j, on the curved
// contact surface of the half disc (2D) and of the half ball (3D), whose
// faces are not parallelograms (the per-face A = D M⁻¹ is not the tensor
// product of the 1D duals there). The standard pairs' M, checked alongside,
// is not diagonal (M_jk ≈ M_jj / 2 between neighbours), so the check can
// fail. A is computed with the contact quadrature that assembles M (the
// faces here are not segmented), so the biorthogonality is exact in the
// discrete sense: the bound is round-off, 1e-12 relative.

#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <iomanip>
#include <map>
#include <sstream>

using namespace dealii;
using namespace StabilizedLagrangian;

namespace
{
  int failures = 0;

  std::string
  scientific(const double value)
  {
    std::ostringstream text;
    text << std::scientific << std::setprecision(2) << value;
    return text.str();
  }

  void
  check(const bool condition, const std::string &message)
  {
    std::cout << (condition ? "  ok: " : "  FAIL: ") << message << std::endl;
    if (!condition)
      ++failures;
  }

  template <int dim>
  std::string
  scene(const std::string &pair)
  {
    return "set Dimension = " + std::to_string(dim) + R"(
subsection Geometry
  set Model = half ball
  subsection half ball
    set Radius = 100
    set Global refinements = 2
    set Local refinements = 0
  end
end
subsection Obstacle
  set Model = plane
  subsection plane
    set Point = )" +
           (dim == 2 ? std::string("0, 0") : std::string("0, 0, 0")) + R"(
    set Normal = )" +
           (dim == 2 ? std::string("0, 1") : std::string("0, 0, 1")) + R"(
  end
end
subsection Contact
  set Contact boundary ids = 2
  set Finite element pair = )" +
           pair + R"(
  set Contact quadrature = Gauss
  set Complementarity = weighted
end
subsection Output
  set Write vtu = false
end
)";
  }

  /**
   * The largest |M_jk| off the diagonal against the diagonal D_jj of its row,
   * and the largest |D_jj − ∫φ_j| / ∫φ_j (∫φ_j: the standard basis's row sum).
   */
  template <int dim>
  std::pair<double, double>
  mass_defects(const std::string &pair, std::map<types::global_dof_index, double> &row_sums)
  {
    ParameterHandler prm;
    Parameters::declare_all<dim>(prm);
    const auto          sections = Parameters::parse<dim>(prm, scene<dim>(pair), false);
    ContactProblem<dim> problem(prm, sections, false);
    problem.setup();
    const auto                                mass = problem.contact_boundary().multiplier_mass();
    std::map<types::global_dof_index, double> diagonal, sums;
    for (const auto &[jk, value] : mass)
      {
        sums[jk.first] += value;
        if (jk.first == jk.second)
          diagonal[jk.first] = value;
      }
    double off_diagonal = 0., diagonal_error = 0.;
    for (const auto &[jk, value] : mass)
      if (jk.first != jk.second)
        off_diagonal = std::max(off_diagonal, std::abs(value) / diagonal.at(jk.first));
    if (row_sums.empty())
      row_sums = sums;
    for (const auto &[j, d] : diagonal)
      diagonal_error = std::max(diagonal_error, std::abs(d - row_sums.at(j)) / row_sums.at(j));
    return {off_diagonal, diagonal_error};
  }

  template <int dim>
  void
  test(const std::string &standard, const double bound)
  {
    std::map<types::global_dof_index, double> row_sums;
    const double standard_off         = mass_defects<dim>(standard, row_sums).first;
    const auto [dual_off, dual_error] = mass_defects<dim>(standard + " dual", row_sums);
    const std::string name            = std::to_string(dim) + "D " + standard;
    check(standard_off > 0.1,
          name + ": the standard basis's M is not diagonal (max |M_jk| / M_jj = " +
              scientific(standard_off) + ")");
    check(dual_off < bound,
          name + " dual: M diagonal, max |M_jk| / M_jj = " + scientific(dual_off) + " (bound " +
              scientific(bound) + ")");
    check(dual_error < bound,
          name + " dual: M_jj = ∫φ_j, max relative difference " + scientific(dual_error));
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // 2D: straight faces, exact to round-off
  test<2>("Q1/P1", 1e-12);
  test<2>("Q2/P2", 1e-12);
  // 3D: curved bilinear faces
  test<3>("Q1/P1", 1e-12);
  test<3>("Q2/P2", 1e-12);
  std::cout << (failures ? "FAILED" : "PASSED") << std::endl;
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
