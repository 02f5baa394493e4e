// J2 plasticity with a tabulated hardening curve, small and finite strain:
// consistent tangent against central differences of the stress (elastic and
// plastic states, equal eigenvalues of b_e), uniaxial stress driven with the
// model's own tangent (the axial stress follows the table, elastic unloading
// has the slope E), objectivity, the small-strain limit of the finite-strain
// model, plane strain against 3D, history written when elastic, rejection of
// J ≤ 0 and of bad input.

#include <stabilized_lagrangian/materials/j2_plasticity.h>

#include "material_test_tools.h"

#include <limits>

using namespace MaterialTestTools;
using Materials::J2Plasticity;
using Materials::Kinematics;

namespace
{
  const double                                 E = 200000., nu = 0.3;
  const std::vector<std::pair<double, double>> table = {
      {0., 194.}, {0.01, 240.}, {0.05, 290.}, {0.1, 320.}, {0.2, 350.}, {0.5, 390.}, {1., 420.}};
  constexpr unsigned int alpha_index = J2Plasticity<3>::equivalent_plastic_strain_index;

  /** The traction curve read off the table by hand: linear, extrapolated past the end. */
  double
  tabulated_yield_stress(const double alpha)
  {
    unsigned int i = 0;
    while (i + 2 < table.size() && alpha >= table[i + 1].first)
      ++i;
    const auto [a0, s0] = table[i];
    const auto [a1, s1] = table[i + 1];
    return s0 + (s1 - s0) / (a1 - a0) * (alpha - a0);
  }

  std::string
  name(const int dim, const Kinematics kinematics)
  {
    return std::to_string(dim) + "D " +
           (kinematics == Kinematics::finite_strain ? "finite strain" : "small strain");
  }

  /**
   * Tangent checks. Besides the rounding ε_mach|σ|/h, the truncation error
   * of a central difference is h²|∂³σ|/6; in a plastic state the flow
   * direction n = s/|s| varies on the scale of the elastic strain
   * σ_y/E ≈ 1e-3, so it is about (h/1e-3)² relative: 1e-6 for h = 1e-6,
   * hence h = 1e-7 here (truncation ~1e-8, rounding and the return map
   * tolerance 1e-14|s| give ~1e-9) and the tolerance 1e-6.
   */
  template <int dim>
  void
  test_tangent(const Kinematics kinematics)
  {
    const J2Plasticity<dim> material(E, nu, kinematics, table);
    std::mt19937            rng(3 + dim + 10 * static_cast<int>(kinematics));
    const double            h          = 1e-7;
    const double            tolerance  = 1e-6;
    const bool              finite     = kinematics == Kinematics::finite_strain;
    const double            large_size = finite ? 0.1 : 5e-3;

    double elastic_error = 0., plastic_error = 0., unloading_error = 0.;
    bool   states_as_intended = true;
    for (unsigned int sample = 0; sample < 5; ++sample)
      {
        const Tensor<2, dim> direction = random_gradient<dim>(rng, 1.);
        const Tensor<2, dim> Q = finite ? random_rotation<dim>(rng) : unit_symmetric_tensor<dim>();

        // elastic from the virgin state (rotated by Q in finite strain)
        MaterialPoint<dim> point(material);
        Tensor<2, dim>     F = random_gradient<dim>(rng, 2e-4);
        for (unsigned int i = 0; i < dim; ++i)
          F[i][i] += 1.;
        const Tensor<2, dim> grad_u_elastic =
            finite ? Tensor<2, dim>(Q * F - unit_symmetric_tensor<dim>())
                   : Tensor<2, dim>(F - unit_symmetric_tensor<dim>());
        point.evaluate(grad_u_elastic);
        states_as_intended &= point.new_history[alpha_index] == 0.;
        elastic_error = std::max(elastic_error, tangent_error(point, grad_u_elastic, direction, h));

        // plastic: commit a plastic state, then load further from it
        const Tensor<2, dim> grad_u_0 = random_gradient<dim>(rng, large_size);
        point.evaluate(grad_u_0);
        point.commit();
        const Tensor<2, dim> grad_u_1 =
            1.2 * grad_u_0 + random_gradient<dim>(rng, 0.1 * large_size);
        point.evaluate(grad_u_1);
        states_as_intended &= point.old_history[alpha_index] > 0. &&
                              point.new_history[alpha_index] > point.old_history[alpha_index];
        plastic_error = std::max(plastic_error, tangent_error(point, grad_u_1, direction, h));

        // elastic unloading from the plastic state (C_p ≠ I in finite strain)
        const Tensor<2, dim> grad_u_2 = 0.99 * grad_u_0;
        point.evaluate(grad_u_2);
        states_as_intended &= point.new_history[alpha_index] == point.old_history[alpha_index];
        unloading_error = std::max(unloading_error, tangent_error(point, grad_u_2, direction, h));
      }
    check(states_as_intended,
          name(dim, kinematics) + " sampled states are elastic/plastic/elastic as intended",
          states_as_intended);
    check_below(elastic_error,
                tolerance,
                name(dim, kinematics) +
                    " elastic tangent vs central difference (max relative error)");
    check_below(plastic_error,
                tolerance,
                name(dim, kinematics) +
                    " plastic tangent vs central difference (max relative error)");
    check_below(unloading_error,
                tolerance,
                name(dim, kinematics) +
                    " tangent after plastic loading, elastic unloading, vs central difference");
  }

  /**
   * Equal eigenvalues of the trial b_e: F = I (all three equal) and a
   * uniaxial plastic stretch (two equal), where ∂ ln b/∂b takes its limit.
   */
  void
  test_tangent_equal_eigenvalues()
  {
    const J2Plasticity<3> material(E, nu, Kinematics::finite_strain, table);
    MaterialPoint<3>      point(material);
    std::mt19937          rng(5);
    const Tensor<2, 3>    direction = random_gradient<3>(rng, 1.);
    const double          h         = 1e-7;

    const double identity_error = tangent_error(point, Tensor<2, 3>(), direction, h);
    check_below(identity_error,
                1e-6,
                "3D finite strain tangent at F = I (triple eigenvalue) vs central difference");

    Tensor<2, 3> uniaxial;
    uniaxial[0][0] = 0.05;
    uniaxial[1][1] = uniaxial[2][2] = -0.024;
    point.evaluate(uniaxial);
    point.commit();
    uniaxial[0][0] = 0.06;
    uniaxial[1][1] = uniaxial[2][2] = -0.029;
    point.evaluate(uniaxial);
    const bool   plastic = point.new_history[alpha_index] > point.old_history[alpha_index];
    const double error   = tangent_error(point, uniaxial, direction, h);
    check(plastic && error < 1e-6,
          "3D finite strain plastic tangent at a double eigenvalue vs central difference",
          error);
  }

  /**
   * Uniaxial stress along x in 3D: the lateral displacement gradients are
   * found by Newton's method with the model's own tangent so that
   * P_yy = P_zz = 0, and the history is committed after every step.
   */
  class UniaxialTest
  {
  public:
    UniaxialTest(const J2Plasticity<3> &material)
        : point(material)
        , finite(material.is_finite_strain())
    {
    }

    /** Set the axial strain (logarithmic in finite strain), solve, commit. */
    void
    step(const double axial_strain)
    {
      grad_u[0][0]                     = finite ? std::exp(axial_strain) - 1. : axial_strain;
      Materials::Response<3> r         = point.evaluate(grad_u);
      unsigned int           iteration = 0;
      while (std::max(std::abs(r.stress[1][1]), std::abs(r.stress[2][2])) > 1e-8)
        {
          const double a = r.tangent[1][1][1][1], b = r.tangent[1][1][2][2],
                       c = r.tangent[2][2][1][1], d = r.tangent[2][2][2][2];
          const double det = a * d - b * c;
          grad_u[1][1] -= (d * r.stress[1][1] - b * r.stress[2][2]) / det;
          grad_u[2][2] -= (-c * r.stress[1][1] + a * r.stress[2][2]) / det;
          r = point.evaluate(grad_u);
          if (++iteration > 30)
            break;
        }
      max_iterations        = std::max(max_iterations, iteration);
      previous_axial_stress = axial_stress;
      previous_alpha        = alpha();
      // Kirchhoff τ_xx = P_xx F_xx (the stress of the yield function) and
      // Cauchy σ_xx = τ_xx / J
      axial_stress = r.stress[0][0] * (finite ? 1. + grad_u[0][0] : 1.);
      axial_cauchy_stress =
          finite ? axial_stress / determinant(unit_symmetric_tensor<3>() + grad_u) : axial_stress;
      point.commit();
    }

    double
    alpha() const
    {
      return point.old_history[alpha_index];
    }

    MaterialPoint<3> point;
    const bool       finite;
    Tensor<2, 3>     grad_u;
    unsigned int     max_iterations        = 0;
    double           axial_stress          = 0.;
    double           axial_cauchy_stress   = 0.;
    double           previous_axial_stress = 0.;
    double           previous_alpha        = 0.;
  };

  void
  test_uniaxial(const Kinematics kinematics)
  {
    const J2Plasticity<3> material(E, nu, kinematics, table);
    UniaxialTest          test(material);
    const std::string     label = name(3, kinematics) + " uniaxial";

    // max relative |τ_xx − σ_y(α)| / σ_y(α) per segment of the table (the
    // last entry: beyond the last point)
    std::vector<double> segment_error(table.size(), -1.);
    double              cauchy_error = 0.;
    const double        increment    = 2e-3;
    unsigned int        n_steps      = 700;
    for (unsigned int n = 1; n <= n_steps; ++n)
      {
        test.step(n * increment);
        if (!(test.alpha() > test.previous_alpha))
          continue;
        unsigned int segment = 0;
        while (segment + 1 < table.size() && test.alpha() >= table[segment + 1].first)
          ++segment;
        const double expected = tabulated_yield_stress(test.alpha());
        segment_error[segment] =
            std::max(segment_error[segment], std::abs(test.axial_stress - expected) / expected);
        // finite strain: det F_p = 1 (deviatoric flow), so J = J_e = exp(tr ε_e) and
        // tr ε_e = τ_xx (1 − 2ν)/E for the Hencky law: σ_xx = σ_y exp(−σ_y (1 − 2ν)/E)
        const double expected_cauchy =
            test.finite ? expected * std::exp(-expected * (1. - 2. * nu) / E) : expected;
        cauchy_error =
            std::max(cauchy_error, std::abs(test.axial_cauchy_stress - expected_cauchy) / expected);
      }
    check(test.max_iterations <= 8,
          label + " lateral Newton with the model's tangent: max iterations",
          test.max_iterations);
    for (unsigned int s = 0; s < table.size(); ++s)
      check(segment_error[s] >= 0. && segment_error[s] < 1e-8,
            label + " stress = tabulated yield stress(alpha), alpha in [" +
                std::to_string(table[s].first).substr(0, 4) + ", " +
                (s + 1 < table.size() ? std::to_string(table[s + 1].first).substr(0, 4)
                                      : std::string("inf")) +
                ") (max relative error)",
            segment_error[s]);
    if (test.finite)
      check_below(
          cauchy_error,
          1e-8,
          label +
              " Cauchy stress = yield stress exp(-yield stress (1 - 2 nu)/E) (max relative error)");
    check(test.alpha() > 1.2, label + " loaded past the last table point: alpha", test.alpha());

    // elastic unloading: slope E (in finite strain dτ_xx/d ln λ_x, exact for
    // the Hencky law with fixed principal axes)
    const double alpha_loaded = test.alpha();
    test.step((n_steps - 0.5) * increment);
    const double slope = (test.axial_stress - test.previous_axial_stress) / (-0.5 * increment);
    check(test.alpha() == alpha_loaded && std::abs(slope - E) < 1e-8 * E,
          label + " elastic unloading slope / E",
          slope / E);
  }

  void
  test_objectivity()
  {
    const J2Plasticity<3> material(E, nu, Kinematics::finite_strain, table);
    std::mt19937          rng(19);
    MaterialPoint<3>      point(material);
    const Tensor<2, 3>    grad_u_0 = random_gradient<3>(rng, 0.1);
    point.evaluate(grad_u_0);
    point.commit();
    const Tensor<2, 3> grad_u = 1.2 * grad_u_0;
    point.evaluate(grad_u);
    const std::vector<double> history = point.new_history;
    const auto [stress_error, tangent_error] =
        objectivity_errors(point, grad_u, random_rotation<3>(rng));
    double history_error = 0.;
    for (unsigned int c = 0; c < history.size(); ++c)
      history_error = std::max(history_error, std::abs(point.new_history[c] - history[c]));
    check(history[alpha_index] > point.old_history[alpha_index],
          "finite strain objectivity checked at a plastic state: alpha",
          history[alpha_index]);
    check_below(stress_error, 1e-10, "finite strain P(QF) = Q P(F) (relative error)");
    check_below(tangent_error, 1e-10, "finite strain A(QF) = Q_ia Q_kb A_aJbL(F) (relative error)");
    check_below(
        history_error,
        1e-12,
        "finite strain history (C_p^-1, alpha) unchanged by the rotation (max |difference|)");
  }

  template <int dim>
  void
  test_small_strain_limit()
  {
    const J2Plasticity<dim> small(E, nu, Kinematics::small_strain, table);
    const J2Plasticity<dim> finite(E, nu, Kinematics::finite_strain, table);
    std::mt19937            rng(23 + dim);
    const auto [tangent_error, stress_error] =
        small_strain_limit_errors(MaterialPoint<dim>(finite), MaterialPoint<dim>(small), rng);
    check_below(tangent_error,
                1e-12,
                std::to_string(dim) + "D finite strain tangent at F = I = small strain (relative)");
    check_below(stress_error,
                1e-5,
                std::to_string(dim) +
                    "D finite strain P at |grad u| ~ 1e-6 = small strain (relative)");
  }

  void
  test_plane_strain(const Kinematics kinematics)
  {
    const J2Plasticity<2> material_2d(E, nu, kinematics, table);
    const J2Plasticity<3> material_3d(E, nu, kinematics, table);
    MaterialPoint<2>      point_2d(material_2d);
    MaterialPoint<3>      point_3d(material_3d);
    std::mt19937          rng(29);
    const double          size     = kinematics == Kinematics::finite_strain ? 0.1 : 5e-3;
    const Tensor<2, 2>    grad_u_0 = random_gradient<2>(rng, size);
    const Tensor<2, 2>    grad_u_1 = 1.3 * grad_u_0;
    point_2d.evaluate(grad_u_0);
    point_2d.commit();
    point_3d.evaluate(Materials::embed_in_3d(grad_u_0));
    point_3d.commit();
    const auto r2 = point_2d.evaluate(grad_u_1);
    const auto r3 = point_3d.evaluate(Materials::embed_in_3d(grad_u_1));

    // in small strain the out-of-plane stress is σ_33 itself (J taken as 1)
    const double J          = kinematics == Kinematics::finite_strain
                                  ? determinant(Materials::deformation_gradient(grad_u_1))
                                  : 1.;
    double       difference = plane_strain_difference(r2, r3, J);
    for (unsigned int c = 0; c < material_2d.n_history(); ++c)
      difference =
          std::max(difference, E * std::abs(point_2d.new_history[c] - point_3d.new_history[c]));
    check(point_2d.new_history[alpha_index] > point_2d.old_history[alpha_index] &&
              difference < 1e-12 * E,
          name(2, kinematics) +
              " plastic state, stress, tangent, history = 3D, sigma_33 (max |difference|)",
          difference);
    check(std::abs(r2.out_of_plane_stress) > 1.,
          name(2, kinematics) + " sigma_33 is not trivially zero",
          r2.out_of_plane_stress);
  }

  template <int dim>
  void
  test_history_when_elastic(const Kinematics kinematics)
  {
    const J2Plasticity<dim> material(E, nu, kinematics, table);
    MaterialPoint<dim>      point(material);
    std::mt19937            rng(31 + dim);
    const Tensor<2, dim>    grad_u =
        random_gradient<dim>(rng, kinematics == Kinematics::finite_strain ? 0.1 : 5e-3);
    point.evaluate(grad_u);
    point.commit();
    std::fill(point.new_history.begin(),
              point.new_history.end(),
              std::numeric_limits<double>::quiet_NaN());
    point.evaluate(0.999 * grad_u);
    check(point.new_history == point.old_history && point.old_history[alpha_index] > 0.,
          name(dim, kinematics) + " elastic step writes new history = old history",
          point.old_history[alpha_index]);
  }

  template <int dim>
  void
  test_inadmissible()
  {
    const J2Plasticity<dim> material(E, nu, Kinematics::finite_strain, table);
    MaterialPoint<dim>      point(material);
    Tensor<2, dim>          inverted;
    inverted[0][0] = -2.;
    const std::string message =
        exception_message<Materials::InadmissibleState>([&]() { point.evaluate(inverted); });
    check(message.find("J = det F") != std::string::npos,
          std::to_string(dim) + "D finite strain J = -1 throws InadmissibleState",
          message.size());
  }

  void
  test_bad_input()
  {
    const std::string curve = "Material/J2 plasticity/Hardening curve";
    const std::vector<std::pair<std::string, std::vector<std::pair<double, double>>>> bad_tables = {
        {"empty", {}},
        {"first plastic strain 0.01", {{0.01, 194.}, {0.1, 240.}}},
        {"repeated plastic strain", {{0., 194.}, {0.1, 240.}, {0.1, 250.}}},
        {"decreasing plastic strain", {{0., 194.}, {0.1, 240.}, {0.05, 250.}}},
        {"zero yield stress", {{0., 0.}, {0.1, 240.}}},
        {"decreasing yield stress", {{0., 194.}, {0.1, 180.}}}};
    for (const auto &[what, points] : bad_tables)
      {
        const std::string message = exception_message<InputError>(
            [&]() { J2Plasticity<3>(E, nu, Kinematics::small_strain, points); });
        check(message.find(curve) == 0,
              "hardening curve with " + what + " gives InputError",
              message.size());
      }
    for (const std::string text : {"0:194, 0.1", "0:abc", "0:194:3", "0:194, 0.1:2e"})
      {
        const std::string message =
            exception_message<InputError>([&]() { Materials::HardeningCurve::parse(text); });
        check(message.find(curve) == 0,
              "hardening curve '" + text + "' gives InputError",
              message.size());
      }
    check(exception_message<InputError>([&]() {
            J2Plasticity<2>(0., nu, Kinematics::small_strain, table);
          }).find("Material/J2 plasticity/Young's modulus") == 0,
          "Young's modulus 0 gives InputError",
          0.);
    check(exception_message<InputError>([&]() {
            J2Plasticity<2>(E, -0.1, Kinematics::small_strain, table);
          }).find("Material/J2 plasticity/Poisson's ratio") == 0,
          "Poisson's ratio -0.1 gives InputError",
          -0.1);
  }

  void
  test_parameters()
  {
    ParameterHandler prm;
    declare_and_choose_model<2>(prm, "J2 plasticity");
    prm.enter_subsection("Material");
    prm.enter_subsection("J2 plasticity");
    const bool default_table =
        Materials::HardeningCurve::parse(prm.get("Hardening curve")) == table;
    prm.set("Kinematics", "finite strain");
    prm.leave_subsection();
    prm.leave_subsection();
    const auto          model = Materials::create<2>(prm);
    std::vector<double> history(model->n_history());
    model->initial_history(make_array_view(history));
    check(default_table && model->is_finite_strain() && model->youngs_modulus() == E &&
              model->poissons_ratio() == nu &&
              history == std::vector<double>{1., 1., 1., 0., 0., 0., 0.},
          "registered as 'J2 plasticity' (default curve, finite strain, C_p^-1 = I initially)",
          model->n_history());

    prm.enter_subsection("Material");
    prm.enter_subsection("J2 plasticity");
    prm.set("Hardening curve", "0:194, 0.1:150");
    prm.leave_subsection();
    prm.leave_subsection();
    check(exception_message<InputError>([&]() {
            Materials::create<2>(prm);
          }).find("Material/J2 plasticity/Hardening curve") == 0,
          "a decreasing curve in the prm gives InputError",
          0.);
  }
} // namespace

int
main()
{
  for (const Kinematics kinematics : {Kinematics::small_strain, Kinematics::finite_strain})
    {
      test_tangent<2>(kinematics);
      test_tangent<3>(kinematics);
      test_uniaxial(kinematics);
      test_plane_strain(kinematics);
      test_history_when_elastic<2>(kinematics);
      test_history_when_elastic<3>(kinematics);
    }
  test_tangent_equal_eigenvalues();
  test_objectivity();
  test_small_strain_limit<2>();
  test_small_strain_limit<3>();
  test_inadmissible<2>();
  test_inadmissible<3>();
  test_bad_input();
  test_parameters();
  return summary();
}
