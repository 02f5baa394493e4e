#include <stabilized_lagrangian/materials/tensor_functions.h>

#include <cmath>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    namespace
    {
      /**
       * θ_ab = (ln x_a − ln x_b)/(x_a − x_b) written as log1p(t)/(t x_b) with
       * t = (x_a − x_b)/x_b, so that near-equal eigenvalues lose no digits;
       * below |t| = 1e-4 the series 1 − t/2 + t²/3 − t³/4 is exact to O(t⁴/5),
       * i.e. to rounding, and gives the limit 1/x_a at t = 0.
       */
      double
      logarithm_divided_difference(const double x_a, const double x_b)
      {
        const double t = (x_a - x_b) / x_b;
        const double log1p_over_t =
            (std::abs(t) < 1e-4) ? 1. - t / 2. + t * t / 3. - t * t * t / 4. : std::log1p(t) / t;
        return log1p_over_t / x_b;
      }
    } // namespace

    double
    admissible_jacobian(const Tensor<2, 3> &F, const std::string &model)
    {
      const double J = determinant(F);
      if (!(J > 0.) || !std::isfinite(J))
        {
          std::ostringstream message;
          message << model << ": J = det F = " << J
                  << "; the material point left its admissible range (J > 0).";
          throw InadmissibleState(message.str());
        }
      return J;
    }

    SymmetricTensor<2, 3>
    isotropic_function(const SymmetricTensor<2, 3> &X, const std::function<double(double)> &y)
    {
      const auto            eigenpairs = eigenvectors(X);
      SymmetricTensor<2, 3> Y;
      for (const auto &[x, n] : eigenpairs)
        Y += y(x) * symmetrize(outer_product(n, n));
      return Y;
    }

    TensorLogarithm
    tensor_logarithm(const SymmetricTensor<2, 3> &X)
    {
      const auto      eigenpairs = eigenvectors(X);
      TensorLogarithm result;
      double          theta[3][3];
      for (unsigned int a = 0; a < 3; ++a)
        {
          const double x_a = eigenpairs[a].first;
          result.value +=
              std::log(x_a) * symmetrize(outer_product(eigenpairs[a].second, eigenpairs[a].second));
          for (unsigned int b = 0; b < 3; ++b)
            theta[a][b] = logarithm_divided_difference(x_a, eigenpairs[b].first);
        }

      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = k; l < 3; ++l)
              {
                double L_ijkl = 0.;
                for (unsigned int a = 0; a < 3; ++a)
                  for (unsigned int b = 0; b < 3; ++b)
                    {
                      const Tensor<1, 3> &n_a = eigenpairs[a].second;
                      const Tensor<1, 3> &n_b = eigenpairs[b].second;
                      L_ijkl +=
                          0.5 * theta[a][b] * n_a[i] * n_b[j] * (n_a[k] * n_b[l] + n_b[k] * n_a[l]);
                    }
                result.derivative[i][j][k][l] = L_ijkl;
              }
      return result;
    }
  } // namespace Materials
} // namespace StabilizedLagrangian
