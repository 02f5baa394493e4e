// Contact residual and Jacobian against central finite differences, with the
// statuses and thresholds frozen as in the innermost Newton loop: points out
// of contact, in contact and sticking, in contact and slipping; 2D and 3D;
// Gauss-Lobatto and Gauss contact quadrature. Then the generalized Newton's
// Jacobian, with the geometry, friction and status loops folded into Newton,
// on a curved obstacle: statuses, thresholds and pairings follow the iterate.
// Then the volume terms of `Volumetric formulation = F-bar` and `mixed`: B-bar
// (linear elastic) and F-bar (neo-Hookean), whose tangent also runs through the
// gradient at each cell's centre, and the condensed three-field formulation
// (Q1/P0, Q2/P1disc), whose tangent runs through every quadrature point's.
// Then `Complementarity = weighted`, frozen and folded: the nodal conditions
// on the weighted gap and slip, whose Λ rows are nonlinear in the slip of the
// node's whole support; also with the dual multiplier basis (Q1/P1 dual).
// Last the axisymmetric model: the hoop strain u_r/r and the weight 2πr in
// the volume and contact terms, small strain and finite strain.

#include <deal.II/base/mpi.h>

#include <deal.II/physics/transformations.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

using namespace dealii;
using namespace StabilizedLagrangian;

namespace
{
  int failures = 0;

  enum class State
  {
    open,
    stick,
    slip,
    mixed
  };

  /** Fold the three outer loops into Newton, on a ball of radius 10 touching the block at x = 1. */
  template <int dim>
  std::string
  generalized_newton()
  {
    return std::string(R"(
subsection Obstacle
  set Model = ball
  subsection ball
    set Radius = 10
    set Center = )") +
           (dim == 2 ? "1, -10" : "1, 0.5, -10") + R"(
  end
end
subsection Nonlinear solver
  subsection Geometry loop
    set Method = newton
  end
  subsection Friction loop
    set Method = newton
  end
  subsection Status loop
    set Method = newton
  end
end
)";
  }

  template <int dim>
  std::string
  scene(const std::string &quadrature, const double mu)
  {
    std::string prm = "set Dimension = " + std::to_string(dim) + "\n" + R"(
subsection Geometry
  set Model = block
  subsection block
    set Length = 2
    set Height = 1
    set Width = 1
    set Subdivisions = )" +
                      std::string(dim == 2 ? "2, 1" : "2, 1, 1") + R"(
    set Global refinements = 1
  end
end
subsection Material
  subsection linear elastic
    # soft, so that the contact terms dominate the displacement rows
    set Young's modulus = 1
  end
end
subsection Contact
  set r_n = 300
  set r_t = 2
  set Contact quadrature = )" +
                      quadrature + R"(
  subsection Friction law
    set Model = Coulomb
    subsection Coulomb
      set Friction coefficient = )" +
                      std::to_string(mu) + R"(
    end
  end
end
subsection Output
  set Write vtu = false
end
)";
    return prm;
  }

  /**
   * The ball of generalized_newton() as a ball at rest elsewhere, turned about
   * the point c by the rotation θ (2D: 0.3 rad; 3D: the rotation vector
   * (0.2, −0.1, 0.3)) and moved by d = (0.1, …): its centre at rest is
   * c + Rᵀ(C − c − d).
   */
  template <int dim>
  std::string
  turned_ball()
  {
    Point<dim> C, c, d;
    C[0]       = 1.;
    C[dim - 1] = -10.;
    if (dim == 3)
      C[1] = 0.5;
    c[0] = -2.;
    c[1] = 3.;
    d[0] = 0.1;
    Tensor<2, dim> R;
    std::string    angle;
    if constexpr (dim == 2)
      {
        R     = Physics::Transformations::Rotations::rotation_matrix_2d(0.3);
        angle = "0.3";
      }
    else
      {
        const Tensor<1, 3> vector({0.2, -0.1, 0.3});
        R     = Physics::Transformations::Rotations::rotation_matrix_3d(vector / vector.norm(),
                                                                    vector.norm());
        angle = "0.2; -0.1; 0.3";
      }
    const Point<dim>   rest = c + transpose(R) * (C - c - d);
    std::ostringstream text;
    text << std::setprecision(17) << generalized_newton<dim>() << "subsection Obstacle\n"
         << "  subsection ball\n    set Center = " << rest[0];
    for (unsigned int i = 1; i < dim; ++i)
      text << ", " << rest[i];
    text << "\n  end\n  subsection Motion\n    set Function expression = 0.1; 0"
         << (dim == 3 ? "; 0" : "") << "\n    set Rotation centre = -2, 3"
         << (dim == 3 ? ", 0" : "")
         << "\n    subsection Rotation\n      set Function expression = " << angle
         << "\n    end\n  end\nend\n";
    return text.str();
  }

  /**
   * Two soft blocks of tests/scenes/two_blocks*.geo touching on non-matching
   * meshes (slave upper_bottom, master lower_top), for the deformable master's
   * linearised pairing: the Jacobian's columns of the master's DoFs. With
   * @p overhang the upper block reaches beyond the lower one
   * (two_blocks_overhang*.geo), so that the closest points of some contact
   * points are held at the master's edge.
   */
  template <int dim>
  std::string
  two_bodies(const bool overhang = false, const std::string &mesh = "")
  {
    return std::string(R"(
subsection Geometry
  set Model = gmsh
  subsection gmsh
    set Mesh file = )") +
           SL_TEST_SCENES +
           (mesh.empty() ? std::string(overhang ? "/two_blocks_overhang" : "/two_blocks") +
                               (dim == 2 ? ".geo" : "_3d.geo")
                         : "/" + mesh) +
           R"(
    set Global refinements = 0
  end
end
subsection Contact
  set Contact boundary ids = upper_bottom
  set Master boundary ids = lower_top
end
)";
  }

  /**
   * @param state the frozen statuses; with @p generalized, the statuses follow
   * the iterate and @p state only chooses the semi-multipliers (stick or slip)
   */
  /**
   * `Volumetric formulation = ` @p formulation (near incompressible,
   * ν = 0.45) with the pair @p pair: with the linear elastic model in small
   * strain, or with the neo-Hookean model (C10 = 0.2: E = 1.16, the soft
   * block of the scene).
   */
  std::string
  volumetric(const std::string &formulation, const std::string &pair, const bool finite_strain)
  {
    return "subsection Contact\n  set Finite element pair = " + pair +
           "\nend\nsubsection Material\n  set Volumetric formulation = " + formulation +
           "\n  set Model = " + (finite_strain ? "neo-Hookean" : "linear elastic") + R"(
  subsection linear elastic
    set Poisson's ratio = 0.45
  end
  subsection neo-Hookean
    set C10 = 0.2
    set Poisson's ratio = 0.45
  end
end
)";
  }

  /**
   * The block as the section of a thick tube about the y axis (r from 0.5 to
   * 2.5), with the linear elastic model or the neo-Hookean one (C10 = 0.2).
   */
  std::string
  axisymmetric(const bool finite_strain)
  {
    return std::string(R"(
subsection Geometry
  set Axisymmetric = true
  subsection block
    set Left side = 0.5
  end
end
)") + (finite_strain ? R"(
subsection Material
  set Model = neo-Hookean
  subsection neo-Hookean
    set C10 = 0.2
  end
end
)"
                     : "");
  }

  template <int dim>
  void
  test(const State        state,
       const std::string &quadrature,
       const double       mu,
       const bool         generalized,
       const std::string &material      = "",
       const double       amplitude     = 1e-3,
       const std::string &label         = "",
       const bool         require_mixed = true)
  {
    ParameterHandler prm;
    Parameters::declare_all<dim>(prm);
    const auto sections = Parameters::parse<dim>(
        prm,
        scene<dim>(quadrature, mu) + (generalized ? generalized_newton<dim>() : "") + material,
        false);
    ContactProblem<dim> problem(prm, sections, false);
    problem.setup();

    const auto multiplier_rows = problem.locally_owned_multiplier_components();
    std::map<types::global_dof_index, unsigned int> component(multiplier_rows.begin(),
                                                              multiplier_rows.end());
    std::mt19937                                    rng(7);
    std::uniform_real_distribution<double>          unit(-1., 1.);

    // state: small displacements (the step started from 0), pressures around 10,
    // semi-multipliers small (stick) or large (slip)
    TrilinosWrappers::MPI::Vector &x = problem.current_solution();
    TrilinosWrappers::MPI::Vector  direction(x);
    for (const auto index : x.locally_owned_elements())
      {
        const bool         is_multiplier = index >= problem.n_displacement_dofs();
        const unsigned int c             = is_multiplier ? component.at(index) : 0;
        double             value         = amplitude * unit(rng);
        if (is_multiplier && c == 0)
          value = 10. + unit(rng);
        else if (is_multiplier)
          value = (state == State::slip ? 3. : 0.2) + 0.05 * unit(rng);
        if (state == State::mixed && is_multiplier && c > 0)
          value = (index % 2 ? 3. : 0.1) + 0.05 * unit(rng);
        x(index)         = value;
        direction(index) = unit(rng) * (is_multiplier ? (c == 0 ? 1. : 0.1) : 1e-3);
      }
    x.compress(VectorOperation::insert);
    direction.compress(VectorOperation::insert);
    problem.update_ghosts();
    if (!generalized)
      for (auto &point : problem.contact_boundary().points())
        {
          point.in_contact         = (state != State::open);
          point.friction_threshold = 5.;
        }
    if (state == State::mixed && !generalized)
      for (unsigned int p = 0; p < problem.contact_boundary().points().size(); p += 3)
        problem.contact_boundary().points()[p].in_contact = false;
    // (weighted: the statuses and thresholds of the nodes, the same pattern)
    if (!generalized)
      problem.contact_boundary().freeze_nodal_conditions(
          [state](const unsigned int k) {
            return state != State::open && !(state == State::mixed && k % 3 == 0);
          },
          5.);

    problem.assemble_newton_system(true);
    unsigned int in_contact = 0;
    for (const auto &point : problem.contact_boundary().points())
      in_contact += point.in_contact;
    // with a curved obstacle the gap |x − c| − R loses digits to cancellation
    // (round-off about r_n R 1e-16 / eps), hence a larger step there
    const double                        eps = generalized ? 1e-5 : 1e-6;
    const TrilinosWrappers::MPI::Vector x0  = x;
    // J v and the central difference of the residual along v
    const auto directional = [&](const TrilinosWrappers::MPI::Vector &v) {
      std::pair<TrilinosWrappers::MPI::Vector, TrilinosWrappers::MPI::Vector> result(x, x);
      problem.jacobian().vmult(result.first, v);
      x = x0;
      x.add(eps, v);
      problem.update_ghosts();
      problem.assemble_newton_system(false);
      result.second = problem.residual();
      x             = x0;
      x.add(-eps, v);
      problem.update_ghosts();
      problem.assemble_newton_system(false);
      result.second.add(-1., problem.residual());
      result.second /= 2. * eps;
      x = x0;
      problem.update_ghosts();
      return result;
    };
    const auto [jv, fd] = directional(direction);
    // The generalized Newton keeps the weight s/r_t of the Λ rows fixed at the
    // iterate (its derivative vanishes at the solution): their λ_n columns are
    // left out by design, so the Λ rows are checked along a direction without
    // λ_n components. The u rows, with the linearised threshold, are checked
    // along the full direction.
    TrilinosWrappers::MPI::Vector no_pressure(direction);
    for (const auto index : x.locally_owned_elements())
      if (index >= problem.n_displacement_dofs() && component.at(index) == 0)
        no_pressure(index) = 0.;
    no_pressure.compress(VectorOperation::insert);
    const auto [jv_lambda, fd_lambda] =
        generalized ? directional(no_pressure) : std::make_pair(jv, fd);

    // compare each block (u, λ_n, Λ) to its own size
    double error[3] = {0., 0., 0.}, size[3] = {0., 0., 0.};
    for (const auto index : x.locally_owned_elements())
      {
        const unsigned int block =
            index < problem.n_displacement_dofs() ? 0 : (component.at(index) == 0 ? 1 : 2);
        const auto &j = block == 2 ? jv_lambda : jv;
        const auto &f = block == 2 ? fd_lambda : fd;
        error[block]  = std::max(error[block], std::abs(j(index) - f(index)));
        size[block]   = std::max(size[block], std::abs(j(index)));
      }
    const char *names[]  = {"open", "stick", "slip", "mixed"};
    const char *blocks[] = {"u", "lambda_n", "Lambda"};
    for (unsigned int b = 0; b < (mu > 0. ? 3 : 2); ++b)
      {
        const double e  = Utilities::MPI::max(error[b], MPI_COMM_WORLD);
        const double s  = Utilities::MPI::max(size[b], MPI_COMM_WORLD);
        const bool   ok = e <= 1e-6 * s && s > 0.;
        failures += !ok;
        if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
          std::cout << (ok ? "ok    " : "FAIL  ") << dim << "D " << label << quadrature
                    << " mu=" << mu << (generalized ? " generalized Newton, " : " ")
                    << names[static_cast<int>(state)] << " rows " << blocks[b]
                    << ": |J v - FD| = " << e << ", |J v| = " << s << std::endl;
      }
    if (generalized && require_mixed)
      {
        // the statuses must really be mixed for the test to mean something
        const unsigned int total = Utilities::MPI::sum(
            static_cast<unsigned int>(problem.contact_boundary().points().size()), MPI_COMM_WORLD);
        const unsigned int active = Utilities::MPI::sum(in_contact, MPI_COMM_WORLD);
        const bool         ok     = active > 0 && active < total;
        failures += !ok;
        if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
          std::cout << (ok ? "ok    " : "FAIL  ") << dim << "D generalized Newton: " << active
                    << " of " << total << " points in contact" << std::endl;
      }
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // every state, law, quadrature and algorithm, with the pointwise and the
  // weighted conditions
  const std::string weighted = "subsection Contact\n  set Complementarity = weighted\nend\n";
  for (const std::string &conditions : {std::string(), weighted})
    for (const std::string quadrature : {"Gauss-Lobatto", "Gauss"})
      for (const State state : {State::open, State::stick, State::slip, State::mixed})
        for (const double mu : {0.3, 0.})
          for (const bool generalized : {false, true})
            {
              if (generalized && state != State::stick && state != State::slip)
                continue;
              const std::string label = conditions.empty() ? "" : "weighted ";
              test<2>(state, quadrature, mu, generalized, conditions, 1e-3, label);
              test<3>(state, quadrature, mu, generalized, conditions, 1e-3, label);
            }
  // the dual multiplier basis (ψ_j = Σ A_jk φ_k per face), weighted conditions
  const std::string dual = "subsection Contact\n  set Complementarity = weighted\n"
                           "  set Finite element pair = Q1/P1 dual\nend\n";
  for (const State state : {State::stick, State::slip, State::mixed})
    for (const bool generalized : {false, true})
      if (!generalized || state != State::mixed)
        {
          test<2>(state, "Gauss", 0.3, generalized, dual, 1e-3, "dual ");
          test<3>(state, "Gauss", 0.3, generalized, dual, 1e-3, "dual ");
        }
  // F-bar's tangent (through the cell centre's gradient) and the mixed one
  // (through the projection from every quadrature point), with displacements
  // of 5 % of the cell size so that the finite-strain terms count
  for (const auto &[formulation, pair] : {std::make_pair("F-bar", "Q1/P1"),
                                          std::make_pair("mixed", "Q1/P1"),
                                          std::make_pair("mixed", "Q2/P2")})
    for (const bool finite_strain : {false, true})
      for (const State state : {State::open, State::slip})
        {
          const std::string label = std::string(formulation) + " " + pair +
                                    (finite_strain ? " neo-Hookean " : " linear elastic ");
          const std::string prm = volumetric(formulation, pair, finite_strain);
          test<2>(state, "Gauss-Lobatto", 0.3, false, prm, 2.5e-2, label);
          test<3>(state, "Gauss-Lobatto", 0.3, false, prm, 2.5e-2, label);
        }
  // the generalized Newton with a deformable master: the pairing (ξ, n, t_α)
  // linearised in the slave's and the master's DoFs, sticking and slipping,
  // with both conditions (every point is in contact: the statuses are not mixed)
  // (pointwise set explicitly: `automatic` takes the weighted conditions for two bodies)
  const std::string pointwise = "subsection Contact\n  set Complementarity = pointwise\nend\n";
  for (const std::string &conditions : {pointwise, weighted, dual})
    for (const State state : {State::stick, State::slip})
      {
        const std::string label =
            std::string("two bodies ") +
            (conditions == pointwise ? "" : (conditions == dual ? "dual " : "weighted "));
        test<2>(state, "Gauss", 0.3, true, two_bodies<2>() + conditions, 1e-3, label, false);
        test<3>(state, "Gauss", 0.3, true, two_bodies<3>() + conditions, 1e-3, label, false);
        // beyond the master's edge: ξ held there, and the gap moving with n
        // through the tangential part of x¹ − x² (without that term the u rows
        // were off by 5 % of |J v| on the 2D slide of tests/two_body_sliding.py)
        test<2>(state,
                "Gauss",
                0.3,
                true,
                two_bodies<2>(true) + conditions,
                1e-3,
                label + "overhanging ",
                false);
        test<3>(state,
                "Gauss",
                0.3,
                true,
                two_bodies<3>(true) + conditions,
                1e-3,
                label + "overhanging ",
                false);
      }
  // a curved deformable master (tests/scenes/block_on_cylinder_3d.geo: the
  // faces of a cylinder's top, their normals 0.11 rad apart), sticking and
  // slipping, the pairing frozen and linearised; displacements of 2e-2 mm
  // bring the points near the crest into contact (the faceted crest lies
  // 0.046 mm below the block)
  for (const bool generalized : {true, false})
    for (const State state : {State::stick, State::slip})
      test<3>(state,
              "Gauss",
              0.3,
              generalized,
              two_bodies<3>(false, "block_on_cylinder_3d.geo") + pointwise,
              2e-2,
              "curved master ");
  // the axisymmetric model (2D): the hoop rows and columns of the tangent,
  // with displacements of 2.5 % of the cell size so that the finite-strain
  // terms count
  for (const bool finite_strain : {false, true})
    for (const State state : {State::open, State::stick, State::slip})
      for (const bool generalized : {false, true})
        if (!generalized || state != State::open)
          test<2>(state,
                  "Gauss-Lobatto",
                  0.3,
                  generalized,
                  axisymmetric(finite_strain),
                  2.5e-2,
                  finite_strain ? "axisymmetric neo-Hookean " : "axisymmetric linear elastic ");
  // a turned obstacle: the ball at rest elsewhere, turned by θ about a point
  // so that it sits where generalized_newton() puts it: its normal's gradient
  // turned by R (doc/formulation.md, "Moving obstacles")
  for (const State state : {State::stick, State::slip})
    {
      test<2>(state, "Gauss-Lobatto", 0.3, true, turned_ball<2>(), 1e-3, "turned obstacle ");
      test<3>(state, "Gauss-Lobatto", 0.3, true, turned_ball<3>(), 1e-3, "turned obstacle ");
    }
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << (failures ? "FAILED" : "PASSED") << std::endl;
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
