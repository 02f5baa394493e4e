#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <functional>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The stress recovered on a boundary face by a least-squares fit over
   * a patch of cells (superconvergent patch recovery, Zienkiewicz and Zhu
   * 1992), for the pressure estimate (doc/formulation.md, "Error estimate").
   *
   * The stress of a degree-p displacement is one order more accurate at the
   * Gauss points of order p of each cell (the Barlow points) than elsewhere,
   * and least accurate on the boundary, where the traction is read. The
   * recovered stress of a face is a polynomial P*(x) fitted, component by
   * component, to the stress at the Barlow points of every cell that shares a
   * vertex with the face's cell (two layers of cells under the face, three
   * cells across it in each tangential direction). Its monomials s^α n^β, in
   * the face's frame (s tangential, n normal, scaled by the face's
   * diameter), have |α| ≤ p + 1, β ≤ p and |α| + β ≤ p + 1: the degree of the
   * exact stress the patch can resolve along the face, one less across it,
   * where only two layers of samples lie. Where the patch has no more samples
   * than monomials (beside a coarser cell, at an edge of the body), it takes
   * one more ring of cells; where that still has too few, the degree drops
   * (p − 1, ..., 1, then the complete linear polynomial, then a constant).
   */
  template <int dim> class StressRecovery
  {
  public:
    using CellIterator = typename DoFHandler<dim>::active_cell_iterator;
    /** The stress at the Barlow points of a cell: (point, stress) pairs. */
    using Sampler =
        std::function<std::vector<std::pair<Point<dim>, Tensor<2, dim>>>(const CellIterator &)>;

    /**
     * @p degree: that of the displacement; @p sampler gives the stress of a
     * locally owned or ghost cell at its Barlow points.
     */
    StressRecovery(const DoFHandler<dim> &dof_handler, unsigned int degree, Sampler sampler);

    /**
     * The recovered stress at @p points of face @p face_no of the locally
     * owned @p cell, @p normal the face's outward unit normal.
     */
    std::vector<Tensor<2, dim>>
    at(const CellIterator            &cell,
       unsigned int                   face_no,
       const Tensor<1, dim>          &normal,
       const std::vector<Point<dim>> &points);

  private:
    /** The stress samples of @p cell, computed once and cached. */
    const std::vector<std::pair<Point<dim>, Tensor<2, dim>>> &
    samples(const CellIterator &cell);

    /**
     * The samples of the patch of @p cell: the cells sharing a vertex with
     * it, and one more ring where those hold no more samples than the fit of
     * full degree has monomials.
     */
    std::vector<std::pair<Point<dim>, Tensor<2, dim>>>
    patch_samples(const CellIterator &cell);

    const DoFHandler<dim>                                                   &dof_handler;
    const unsigned int                                                       degree;
    Sampler                                                                  sampler;
    std::vector<std::set<typename Triangulation<dim>::active_cell_iterator>> vertex_cells;
    std::unordered_map<unsigned int, std::vector<std::pair<Point<dim>, Tensor<2, dim>>>> cache;
  };
} // namespace StabilizedLagrangian
