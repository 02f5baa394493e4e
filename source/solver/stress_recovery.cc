#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <stabilized_lagrangian/contact/pairing.h>
#include <stabilized_lagrangian/solver/stress_recovery.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace StabilizedLagrangian
{
  namespace
  {
    /**
     * The exponents (tangential..., normal) of the monomials s^α n^β with
     * |α| + β ≤ total and β ≤ across.
     */
    template <int dim>
    std::vector<std::array<unsigned int, dim>>
    monomials(const unsigned int total, const unsigned int across)
    {
      std::vector<std::array<unsigned int, dim>> result;
      for (unsigned int b = 0; b <= across; ++b)
        for (unsigned int a0 = 0; a0 + b <= total; ++a0)
          for (unsigned int a1 = 0; a1 == 0 || (dim == 3 && a1 + a0 + b <= total); ++a1)
            {
              std::array<unsigned int, dim> e{};
              e[0]       = a0;
              e[1]       = a1;
              e[dim - 1] = b;
              result.push_back(e);
            }
      return result;
    }

    /** The monomial with the exponents @p e at the point @p local (face coordinates). */
    template <int dim>
    double
    monomial(const std::array<unsigned int, dim> &e, const Point<dim> &local)
    {
      double value = 1.;
      for (unsigned int d = 0; d < dim; ++d)
        value *= std::pow(local[d], static_cast<int>(e[d]));
      return value;
    }

    /**
     * The coordinates of a point in a boundary face's frame: tangents, then
     * the outward normal, about the face's centre, in face diameters.
     */
    template <int dim> class FaceCoordinates
    {
    public:
      template <typename FaceIterator>
      FaceCoordinates(const FaceIterator &face, const Tensor<1, dim> &normal)
          : centre(face->center())
          , h(face->diameter())
      {
        const auto tangents = Contact::tangent_basis(normal);
        std::copy(tangents.begin(), tangents.end(), frame.begin());
        frame[dim - 1] = normal;
      }

      /** The coordinates of @p x. */
      Point<dim>
      operator()(const Point<dim> &x) const
      {
        Point<dim> y;
        for (unsigned int d = 0; d < dim; ++d)
          y[d] = (x - centre) * frame[d] / h;
        return y;
      }

    private:
      std::array<Tensor<1, dim>, dim> frame;
      Point<dim>                      centre;
      double                          h;
    };

    /**
     * The exponents of the fit's space for @p n_samples samples: degree p + 1
     * along the face and p across it for p = @p degree, then smaller ones
     * while the patch still has no more samples than monomials (p − 1, ...,
     * 1, then linear, then constant).
     */
    template <int dim>
    std::vector<std::array<unsigned int, dim>>
    fit_exponents(const unsigned int degree, const std::size_t n_samples)
    {
      std::vector<std::array<unsigned int, dim>> exponents = monomials<dim>(degree + 1, degree);
      for (unsigned int p = degree - 1; p >= 1 && exponents.size() >= n_samples; --p)
        exponents = monomials<dim>(p + 1, p);
      if (exponents.size() >= n_samples)
        exponents = monomials<dim>(1, 1);
      if (exponents.size() >= n_samples)
        exponents = monomials<dim>(0, 0);
      return exponents;
    }

    /**
     * The least-squares coefficients (monomial, stress component) of the
     * polynomial with @p exponents fitted to the stress @p samples, the
     * points in the coordinates @p local; the normal equations are solved by
     * the pseudo-inverse, singular values below 1e-12 of its trace left out.
     */
    template <int dim>
    FullMatrix<double>
    least_squares_fit(const std::vector<std::pair<Point<dim>, Tensor<2, dim>>> &samples,
                      const std::vector<std::array<unsigned int, dim>>         &exponents,
                      const FaceCoordinates<dim>                               &local)
    {
      const unsigned int       n = exponents.size();
      LAPACKFullMatrix<double> normal_matrix(n, n);
      FullMatrix<double>       moments(n, dim * dim);
      std::vector<double>      basis(n);
      for (const auto &[x, stress] : samples)
        {
          const Point<dim> y = local(x);
          for (unsigned int i = 0; i < n; ++i)
            basis[i] = monomial<dim>(exponents[i], y);
          for (unsigned int i = 0; i < n; ++i)
            {
              for (unsigned int j = 0; j < n; ++j)
                normal_matrix(i, j) += basis[i] * basis[j];
              for (unsigned int c = 0; c < dim * dim; ++c)
                moments(i, c) += basis[i] * stress[c / dim][c % dim];
            }
        }
      double trace = 0.;
      for (unsigned int i = 0; i < n; ++i)
        trace += normal_matrix(i, i);
      normal_matrix.compute_inverse_svd(1e-12 * trace);
      FullMatrix<double> coefficients(n, dim * dim);
      Vector<double>     column(n), solution(n);
      for (unsigned int c = 0; c < dim * dim; ++c)
        {
          for (unsigned int i = 0; i < n; ++i)
            column[i] = moments(i, c);
          normal_matrix.vmult(solution, column);
          for (unsigned int i = 0; i < n; ++i)
            coefficients(i, c) = solution[i];
        }
      return coefficients;
    }
  } // namespace

  template <int dim>
  StressRecovery<dim>::StressRecovery(const DoFHandler<dim> &dof_handler,
                                      const unsigned int     degree,
                                      Sampler                sampler)
      : dof_handler(dof_handler)
      , degree(degree)
      , sampler(std::move(sampler))
      , vertex_cells(GridTools::vertex_to_cell_map(dof_handler.get_triangulation()))
  {
  }

  template <int dim>
  const std::vector<std::pair<Point<dim>, Tensor<2, dim>>> &
  StressRecovery<dim>::samples(const CellIterator &cell)
  {
    const auto found = cache.find(cell->active_cell_index());
    if (found != cache.end())
      return found->second;
    return cache.emplace(cell->active_cell_index(), sampler(cell)).first->second;
  }

  template <int dim>
  std::vector<std::pair<Point<dim>, Tensor<2, dim>>>
  StressRecovery<dim>::patch_samples(const CellIterator &cell)
  {
    // the patch: every cell sharing a vertex with cell (a hanging vertex
    // brings the coarse cell whose face holds it); one more ring of cells
    // where that holds too few samples for the fit's space (beside a coarser
    // cell, at an edge of the body)
    std::set<typename Triangulation<dim>::active_cell_iterator> patch{cell};
    const auto                                                  add_ring = [&]() {
      const auto inner = patch;
      for (const auto &member : inner)
        for (const unsigned int v : member->vertex_indices())
          for (const auto &neighbor : vertex_cells[member->vertex_index(v)])
            if (!neighbor->is_artificial())
              patch.insert(neighbor);
    };
    const auto gather = [&]() {
      std::vector<std::pair<Point<dim>, Tensor<2, dim>>> all;
      for (const auto &member : patch)
        {
          const auto &s = samples(CellIterator(
              &dof_handler.get_triangulation(), member->level(), member->index(), &dof_handler));
          all.insert(all.end(), s.begin(), s.end());
        }
      return all;
    };
    add_ring();
    auto all = gather();
    if (all.size() <= monomials<dim>(degree + 1, degree).size())
      {
        add_ring();
        all = gather();
      }
    return all;
  }

  template <int dim>
  std::vector<Tensor<2, dim>>
  StressRecovery<dim>::at(const CellIterator            &cell,
                          const unsigned int             face_no,
                          const Tensor<1, dim>          &normal,
                          const std::vector<Point<dim>> &points)
  {
    const std::vector<std::pair<Point<dim>, Tensor<2, dim>>> all = patch_samples(cell);
    const FaceCoordinates<dim>                               local(cell->face(face_no), normal);
    const std::vector<std::array<unsigned int, dim>>         exponents =
        fit_exponents<dim>(degree, all.size());
    const unsigned int       n            = exponents.size();
    const FullMatrix<double> coefficients = least_squares_fit<dim>(all, exponents, local);

    std::vector<Tensor<2, dim>> result(points.size());
    for (unsigned int q = 0; q < points.size(); ++q)
      {
        const Point<dim> y = local(points[q]);
        for (unsigned int i = 0; i < n; ++i)
          {
            const double b = monomial<dim>(exponents[i], y);
            for (unsigned int c = 0; c < dim * dim; ++c)
              result[q][c / dim][c % dim] += b * coefficients(i, c);
          }
      }
    return result;
  }

  template class StressRecovery<2>;
  template class StressRecovery<3>;
} // namespace StabilizedLagrangian
