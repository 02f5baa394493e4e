// Helpers shared by the unit tests of the material models: ok/FAIL
// reporting (check_tools.h), random displacement gradients and rotations, and central
// differences of the stress.

#pragma once

#include "check_tools.h"

#include <stabilized_lagrangian/materials/material.h>
#include <stabilized_lagrangian/materials/tensor_functions.h>

#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace MaterialTestTools
{
  using namespace dealii;
  using namespace StabilizedLagrangian;

  using namespace CheckTools;

  /** Tensor with components uniform in [−size, size]. */
  template <int dim>
  Tensor<2, dim>
  random_gradient(std::mt19937 &rng, const double size)
  {
    std::uniform_real_distribution<double> dist(-size, size);
    Tensor<2, dim>                         h;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        h[i][j] = dist(rng);
    return h;
  }

  /** Random proper rotation: about e_3 in 2D, about a random axis in 3D (Rodrigues). */
  template <int dim>
  Tensor<2, dim>
  random_rotation(std::mt19937 &rng)
  {
    std::uniform_real_distribution<double> dist(-1., 1.);
    const double                           angle = 3. * dist(rng);
    Tensor<2, dim>                         Q;
    if constexpr (dim == 2)
      {
        Q[0][0] = Q[1][1] = std::cos(angle);
        Q[1][0]           = std::sin(angle);
        Q[0][1]           = -std::sin(angle);
      }
    else
      {
        Tensor<1, dim> axis;
        for (unsigned int i = 0; i < dim; ++i)
          axis[i] = dist(rng);
        axis /= axis.norm();
        Tensor<2, dim> K; // K v = axis × v
        K[0][1] = -axis[2];
        K[0][2] = axis[1];
        K[1][2] = -axis[0];
        K       = K - transpose(K);
        Q       = std::sin(angle) * K + (1. - std::cos(angle)) * K * K;
        for (unsigned int i = 0; i < dim; ++i)
          Q[i][i] += 1.;
      }
    return Q;
  }

  /** Rotated tangent Q_ia Q_kb A_aJbL: the tangent at QF of an objective model. */
  template <int dim>
  Tensor<4, dim>
  rotate_tangent(const Tensor<4, dim> &A, const Tensor<2, dim> &Q)
  {
    Tensor<4, dim> result;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int J = 0; J < dim; ++J)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int L = 0; L < dim; ++L)
            for (unsigned int a = 0; a < dim; ++a)
              for (unsigned int b = 0; b < dim; ++b)
                result[i][J][k][L] += Q[i][a] * Q[k][b] * A[a][J][b][L];
    return result;
  }

  /** A model together with the history it is evaluated from. */
  template <int dim> struct MaterialPoint
  {
    const Materials::Interface<dim> &material;
    std::vector<double>              old_history;
    mutable std::vector<double>      new_history;

    explicit MaterialPoint(const Materials::Interface<dim> &material)
        : material(material)
        , old_history(material.n_history())
        , new_history(material.n_history())
    {
      material.initial_history(make_array_view(old_history));
    }

    /** Evaluate from old_history, writing new_history. */
    Materials::Response<dim>
    evaluate(const Tensor<2, dim> &grad_u) const
    {
      return material.evaluate(grad_u,
                               ArrayView<const double>(old_history.data(), old_history.size()),
                               make_array_view(new_history));
    }

    /** Accept the state of the last evaluation (a converged load step). */
    void
    commit()
    {
      old_history = new_history;
    }
  };

  /**
   * Relative error between the tangent applied to a direction and the
   * central difference of the stress, (P(∇u + h d) − P(∇u − h d))/(2h),
   * both evaluated from the same old history.
   */
  template <int dim>
  double
  tangent_error(const MaterialPoint<dim> &point,
                const Tensor<2, dim>     &grad_u,
                const Tensor<2, dim>     &direction,
                const double              h)
  {
    const Tensor<2, dim> exact =
        double_contract<2, 0, 3, 1>(point.evaluate(grad_u).tangent, direction);
    const Tensor<2, dim> fd = (point.evaluate(grad_u + h * direction).stress -
                               point.evaluate(grad_u - h * direction).stress) /
                              (2. * h);
    return (fd - exact).norm() / exact.norm();
  }

  /** Declare the `Material` subsection in @p prm and choose the model @p name. */
  template <int dim>
  void
  declare_and_choose_model(ParameterHandler &prm, const std::string &name)
  {
    Materials::declare_parameters<dim>(prm);
    prm.enter_subsection("Material");
    prm.set("Model", name);
    prm.leave_subsection();
  }

  /** The message of the @p Exception thrown by @p action, or "" if none is thrown. */
  template <typename Exception, typename Function>
  std::string
  exception_message(const Function &action)
  {
    try
      {
        action();
      }
    catch (const Exception &e)
      {
        return e.what();
      }
    return "";
  }

  /**
   * Relative errors of P(QF) = Q P(F) and of A_iJkL(QF) = Q_ia Q_kb A_aJbL(F)
   * (frame indifference), both from the same old history; the point keeps
   * the new history of QF.
   */
  template <int dim>
  std::pair<double, double>
  objectivity_errors(const MaterialPoint<dim> &point,
                     const Tensor<2, dim>     &grad_u,
                     const Tensor<2, dim>     &Q)
  {
    Tensor<2, dim> F = grad_u;
    for (unsigned int i = 0; i < dim; ++i)
      F[i][i] += 1.;
    const auto response = point.evaluate(grad_u);
    const auto rotated  = point.evaluate(Q * F - unit_symmetric_tensor<dim>());
    return {(rotated.stress - Q * response.stress).norm() / response.stress.norm(),
            (rotated.tangent - rotate_tangent(response.tangent, Q)).norm() /
                response.tangent.norm()};
  }

  /**
   * Small-strain limit of a finite-strain model against a small-strain one:
   * the relative difference of the tangents at ∇u = 0 (zero up to rounding)
   * and of the stresses at a random ∇u of size 1e-6 (P − σ = O(|∇u|) σ, so
   * about 1e-6 relative).
   */
  template <int dim>
  std::pair<double, double>
  small_strain_limit_errors(const MaterialPoint<dim> &finite_strain,
                            const MaterialPoint<dim> &small_strain,
                            std::mt19937             &rng)
  {
    const Tensor<4, dim> A      = finite_strain.evaluate(Tensor<2, dim>()).tangent;
    const Tensor<4, dim> C      = small_strain.evaluate(Tensor<2, dim>()).tangent;
    const Tensor<2, dim> grad_u = random_gradient<dim>(rng, 1e-6);
    const Tensor<2, dim> P      = finite_strain.evaluate(grad_u).stress;
    const Tensor<2, dim> sigma  = small_strain.evaluate(grad_u).stress;
    return {(A - C).norm() / C.norm(), (P - sigma).norm() / sigma.norm()};
  }

  /**
   * Largest difference between a plane-strain response and the 3D response
   * at the embedded displacement gradient: in-plane stress and tangent
   * blocks, and the out-of-plane Cauchy stress against P_33 / J of the 3D
   * response (F_33 = 1, so σ_33 = (P Fᵀ)_33 / J = P_33 / J).
   */
  inline double
  plane_strain_difference(const Materials::Response<2> &plane_strain,
                          const Materials::Response<3> &response_3d,
                          const double                  J)
  {
    const Tensor<2, 2> stress_error =
        plane_strain.stress - Materials::in_plane_block<2>(response_3d.stress);
    const Tensor<4, 2> tangent_error =
        plane_strain.tangent - Materials::in_plane_block<2>(response_3d.tangent);
    double difference = std::abs(plane_strain.out_of_plane_stress - response_3d.stress[2][2] / J);
    for (unsigned int c = 0; c < Tensor<2, 2>::n_independent_components; ++c)
      difference = std::max(difference,
                            std::abs(stress_error[Tensor<2, 2>::unrolled_to_component_indices(c)]));
    for (unsigned int c = 0; c < Tensor<4, 2>::n_independent_components; ++c)
      difference = std::max(
          difference, std::abs(tangent_error[Tensor<4, 2>::unrolled_to_component_indices(c)]));
    return difference;
  }
} // namespace MaterialTestTools
