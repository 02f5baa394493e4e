#pragma once

#include <deal.II/base/array_view.h>

#include <deal.II/grid/tria.h>

#include <stabilized_lagrangian/materials/material.h>

#include <algorithm>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    /**
     * @brief History variables of the material at every quadrature point of
     * the active cells.
     *
     * Two copies are kept: the committed values, from the end of the last
     * converged load step, which every evaluation starts from, and the trial
     * values written by the evaluation at the current iterate. commit() makes
     * the trial values the committed ones; it is called only when a load step
     * has converged, so a failed (cut) step leaves no trace.
     */
    class QuadratureHistory
    {
    public:
      /**
       * @brief Size the storage for @p n_quadrature_points points per active
       * cell of @p triangulation and set the initial values of the material
       * of each cell, @p material_of(cell) (a const Interface<dim>&).
       */
      template <int dim, typename MaterialOf>
      void
      initialize(const Triangulation<dim> &triangulation,
                 const unsigned int        n_quadrature_points,
                 const MaterialOf         &material_of)
      {
        n_points_per_cell = n_quadrature_points;
        cell_values.assign(triangulation.n_active_cells(), 0);
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->is_artificial())
            cell_values[cell->active_cell_index()] = material_of(cell).n_history();
        n_values =
            cell_values.empty() ? 0 : *std::max_element(cell_values.begin(), cell_values.end());
        committed_values.assign(static_cast<std::size_t>(triangulation.n_active_cells()) *
                                    n_points_per_cell * n_values,
                                0.);
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->is_artificial() && cell_values[cell->active_cell_index()] > 0)
            for (unsigned int q = 0; q < n_points_per_cell; ++q)
              material_of(cell).initial_history(
                  ArrayView<double>(committed_values.data() + offset(cell->active_cell_index(), q),
                                    cell_values[cell->active_cell_index()]));
        trial_values = committed_values;
      }

      /** @brief Committed values at point @p q of the active cell @p cell_index. */
      ArrayView<const double>
      committed(const unsigned int cell_index, const unsigned int q) const
      {
        if (cell_values[cell_index] == 0)
          return {};
        return {committed_values.data() + offset(cell_index, q), cell_values[cell_index]};
      }

      /** @brief Trial values at point @p q of the active cell @p cell_index. */
      ArrayView<double>
      trial(const unsigned int cell_index, const unsigned int q)
      {
        if (cell_values[cell_index] == 0)
          return {};
        return {trial_values.data() + offset(cell_index, q), cell_values[cell_index]};
      }

      /** @brief The committed values of every point of the active cell @p cell_index. */
      std::vector<double>
      committed_cell(const unsigned int cell_index) const
      {
        const auto begin = committed_values.begin() + offset(cell_index, 0);
        return {begin, begin + static_cast<std::ptrdiff_t>(n_points_per_cell * n_values)};
      }
      /**
       * @brief Set the committed values of the active cell @p cell_index from
       * committed_cell() of its owner (a ghost cell's history for the error
       * estimate; never assembled).
       */
      void
      set_committed_cell(const unsigned int cell_index, const std::vector<double> &values)
      {
        AssertDimension(values.size(), n_points_per_cell * n_values);
        std::copy(values.begin(), values.end(), committed_values.begin() + offset(cell_index, 0));
      }
      /** @brief Accept the trial values of a converged load step. */
      void
      commit()
      {
        committed_values = trial_values;
      }

      /** @brief The committed values of every cell (for a checkpoint). */
      const std::vector<double> &
      committed_data() const
      {
        return committed_values;
      }

      /** @brief Restore committed (and trial) values saved by committed_data() on this mesh. */
      void
      restore(const std::vector<double> &values)
      {
        AssertThrow(values.size() == committed_values.size(),
                    ExcMessage("the checkpoint's material history does not fit this mesh"));
        committed_values = values;
        trial_values     = values;
      }

    private:
      std::size_t
      offset(const unsigned int cell_index, const unsigned int q) const
      {
        return (static_cast<std::size_t>(cell_index) * n_points_per_cell + q) * n_values;
      }

      unsigned int              n_points_per_cell = 0;
      unsigned int              n_values          = 0; ///< the stride: the largest per cell
      std::vector<unsigned int> cell_values;           ///< history values of each cell's material
      std::vector<double>       committed_values;
      std::vector<double>       trial_values;
    };
  } // namespace Materials
} // namespace StabilizedLagrangian
