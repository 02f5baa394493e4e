#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/contact/contact_edge.h>
#include <stabilized_lagrangian/contact/pairing.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    template <int dim>
    SquareRootOnset<dim>::SquareRootOnset(const std::vector<Point<dim>> &points,
                                          const std::vector<bool>       &in_contact,
                                          const std::vector<double>     &pressures,
                                          const std::vector<double>     &gaps,
                                          const Tensor<1, dim>          &normal,
                                          const double                   modulus)
    {
      const unsigned int n = points.size();
      const auto         n_in =
          static_cast<unsigned int>(std::count(in_contact.begin(), in_contact.end(), true));
      if (n_in == 0 || n_in == n || n < static_cast<unsigned int>(dim))
        return;
      const auto tangents = tangent_basis(normal);
      origin              = points[0];
      for (unsigned int k = 1; k < n; ++k)
        origin += (points[k] - points[0]) / n;

      // d_k = c⁻² A_k − c^{−2/3} B_k; the least-squares affine fit of d is
      // linear in the d_k, so its gradient is c⁻² β_A − c^{−2/3} β_B
      FullMatrix<double> normal_matrix(dim, dim);
      Vector<double>     rhs_a(dim), rhs_b(dim), beta_a(dim), beta_b(dim);
      double             scale = 0.;
      for (unsigned int k = 0; k < n; ++k)
        {
          std::array<double, dim> row{};
          row[0] = 1.;
          for (unsigned int t = 0; t + 1 < dim; ++t)
            row[t + 1] = (points[k] - origin) * tangents[t];
          const double a = in_contact[k] ? std::pow(std::max(pressures[k], 0.), 2) : 0.;
          const double b =
              in_contact[k] ? 0. : std::pow(0.75 * modulus * std::max(gaps[k], 0.), 2. / 3.);
          for (unsigned int i = 0; i < dim; ++i)
            {
              for (unsigned int j = 0; j < dim; ++j)
                normal_matrix(i, j) += row[i] * row[j];
              rhs_a(i) += row[i] * a;
              rhs_b(i) -= row[i] * b;
            }
          scale = std::max(scale, in_contact[k] ? std::max(pressures[k], 0.) : 0.);
        }
      if (scale <= 0.)
        return;
      // a face whose points do not span it (all on one line in 3D) has no fit
      double diagonal = 0.;
      for (unsigned int i = 0; i < dim; ++i)
        diagonal = std::max(diagonal, normal_matrix(i, i));
      FullMatrix<double> inverse(dim, dim);
      if (std::abs(normal_matrix.determinant()) < 1e-12 * std::pow(diagonal, dim))
        return;
      inverse.invert(normal_matrix);
      inverse.vmult(beta_a, rhs_a);
      inverse.vmult(beta_b, rhs_b);
      const auto gradient_at = [&](const double cc) {
        Tensor<1, dim> g;
        for (unsigned int t = 0; t + 1 < dim; ++t)
          g += (beta_a(t + 1) / (cc * cc) + beta_b(t + 1) / std::cbrt(cc * cc)) * tangents[t];
        return g;
      };
      // |∇d| falls from ∞ to 0 as c grows: bisection on log c
      double low = std::log(scale * 1e-6), high = std::log(scale * 1e6);
      if (gradient_at(std::exp(low)).norm() < 1. || gradient_at(std::exp(high)).norm() > 1.)
        return;
      for (unsigned int i = 0; i < 200 && high - low > 1e-12; ++i)
        {
          const double middle                                      = 0.5 * (low + high);
          (gradient_at(std::exp(middle)).norm() > 1. ? low : high) = middle;
        }
      c        = std::exp(0.5 * (low + high));
      gradient = gradient_at(c);
      offset   = beta_a(0) / (c * c) + beta_b(0) / std::cbrt(c * c);
      fitted   = std::isfinite(c) && std::isfinite(offset);
    }

    template <int dim>
    double
    SquareRootOnset<dim>::distance(const Point<dim> &x) const
    {
      return offset + gradient * (x - origin);
    }

    template <int dim>
    double
    SquareRootOnset<dim>::pressure(const Point<dim> &x) const
    {
      return c * std::sqrt(std::max(distance(x), 0.));
    }

    template class SquareRootOnset<2>;
    template class SquareRootOnset<3>;
  } // namespace Contact
} // namespace StabilizedLagrangian
