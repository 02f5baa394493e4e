#pragma once

#include <deal.II/base/array_view.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/discretization/fe_pair.h>
#include <stabilized_lagrangian/geometry/body_mesh.h>
#include <stabilized_lagrangian/materials/f_bar.h>
#include <stabilized_lagrangian/materials/material.h>
#include <stabilized_lagrangian/materials/quadrature_history.h>

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

/**
 * @file
 * The material response of the bodies: which model and volumetric
 * formulation each cell has, and the response P, ∂P/∂F of a point, with the
 * F-bar and mixed formulations (doc/formulation.md, "Near incompressibility";
 * materials/f_bar.h) and the hoop strain of an axisymmetric model.
 */

namespace StabilizedLagrangian
{
  namespace Materials
  {
    using namespace dealii;

    /**
     * @brief The bodies' material response: the material slots (the default
     * model `Material` first, then `Material 2`, ...), the model and
     * formulation of each cell (by its body, BodyMesh::material_slot()), the
     * response at a point from a history, and the F-bar fields of a
     * displacement (∇u at each cell's centre, the coefficients of each cell's
     * kept volume change) that the output and the error estimate evaluate the
     * committed state with.
     *
     * It owns the slots and the F-bar fields; it reads the mesh, the
     * displacement's element, DoFs and quadrature, and the committed material
     * history, all members of the problem that built it.
     */
    template <int dim> class BodyResponse
    {
    public:
      /** A cell of the bodies' mesh (any DoFHandler's cell converts to it). */
      using Cell = typename Triangulation<dim>::cell_iterator;

      /**
       * @brief The response of the bodies of @p body_mesh, with no slots yet (set_slots()).
       * @param history the material history (its committed values are read)
       * @param fe_pair, fe_u, dof_handler_u, cell_quadrature the displacement's
       * pair, element, DoFs and cell rule, as the problem holds them (they may
       * be set after this object is built)
       * @param axisymmetric `Geometry/Axisymmetric`
       */
      BodyResponse(const BodyMesh<dim>                                &body_mesh,
                   const QuadratureHistory                            &history,
                   const std::unique_ptr<Discretization::FEPair<dim>> &fe_pair,
                   const std::unique_ptr<FiniteElement<dim>>          &fe_u,
                   const DoFHandler<dim>                              &dof_handler_u,
                   const Quadrature<dim>                              &cell_quadrature,
                   const bool                                          axisymmetric)
          : body_mesh(body_mesh)
          , history(history)
          , fe_pair(fe_pair)
          , fe_u(fe_u)
          , dof_handler_u(dof_handler_u)
          , cell_quadrature(cell_quadrature)
          , axisymmetric(axisymmetric)
      {
      }

      /** @brief Take the material slots (Materials::create_all()). */
      void
      set_slots(std::vector<BodyMaterial<dim>> &&slots)
      {
        materials = std::move(slots);
      }

      /** @brief The default model first, then the slots in use. */
      const std::vector<BodyMaterial<dim>> &
      slots() const
      {
        return materials;
      }

      /** @brief Whether any material is finite strain. */
      bool
      finite_strain() const
      {
        return std::any_of(materials.begin(), materials.end(), [](const auto &body) {
          return body.model->is_finite_strain();
        });
      }

      /** @brief The material of a cell (by its body, `Material 2`, `Material 3`, else `Material`).
       */
      const Interface<dim> &
      material_of(const Cell &cell) const
      {
        return *body_of(cell).model;
      }

      /** @brief The material slot of a cell: its model and formulation. */
      const BodyMaterial<dim> &
      body_of(const Cell &cell) const
      {
        return materials[body_mesh.material_slot(cell->material_id())];
      }

      /**
       * @brief The hoop strain u_r / r at @p x of an axisymmetric model, 0 otherwise;
       * on the axis its limit ∂u_r/∂r (u_r = 0 there), from @p grad_u.
       */
      double
      hoop_strain(const Point<dim> &x, const Tensor<1, dim> &u, const Tensor<2, dim> &grad_u) const
      {
        if (!axisymmetric)
          return 0.;
        return x[0] > 0. ? u[0] / x[0] : grad_u[0][0];
      }

      /**
       * @brief The response of @p cell's material at its quadrature point @p q
       * (the history's) or reference point @p unit for @p grad_u, from the
       * committed history (that of the last converged state); the updated
       * history is discarded. With F-bar and mixed, ∂P̃/∂v̄ into @p d_kept when
       * given, from the fields of compute_volume_fields(); in an axisymmetric
       * model @p hoop is the hoop strain u_r/r. For the output and the error
       * estimate, never the assembly.
       */
      Response<dim>
      committed_response(const Cell           &cell,
                         const unsigned int    q,
                         const Point<dim>     &unit,
                         const Tensor<2, dim> &grad_u,
                         Tensor<2, dim>       *d_kept = nullptr,
                         const double          hoop   = 0.) const
      {
        const auto          committed = history.committed(cell->active_cell_index(), q);
        std::vector<double> discarded(committed.size());
        const auto         &body = body_of(cell);
        if (!body.modified_volume())
          return body.model->evaluate(grad_u, committed, make_array_view(discarded), hoop);
        // The estimate evaluates the stress between the quadrature points too,
        // where a cell whose quadrature points are admissible may be inverted
        // (J ≤ 0 at a face point of an hourglassing cell): there, the centre's state.
        const unsigned int          index      = cell->active_cell_index();
        const VolumeProjection<dim> projection = volume_projection(body);
        const bool                  finite     = body.model->is_finite_strain();
        const double                kept = projection.value(kept_volume_coefficients[index], unit);
        const bool                  admissible =
            !finite || (determinant(unit_symmetric_tensor<dim>() + grad_u) > 0. && kept > 0.);
        return material_response(body,
                                 admissible ? grad_u : centre_gradients[index],
                                 admissible ? kept : kept_volume_coefficients[index][0],
                                 committed,
                                 make_array_view(discarded),
                                 d_kept);
      }

      /**
       * @brief The response of @p body's model at one quadrature point from the
       * history @p committed (the updated one into @p trial): P and ∂P/∂F at
       * @p grad_u; with F-bar or mixed the weak-form stress P̃, ∂P̃/∂F and, into
       * @p d_kept when given, ∂P̃/∂v̄ for the volume change @p kept the point
       * keeps (include/stabilized_lagrangian/materials/f_bar.h); @p hoop: the hoop
       * strain u_r/r of an axisymmetric model (displacement formulation only).
       */
      Response<dim>
      material_response(const BodyMaterial<dim>       &body,
                        const Tensor<2, dim>          &grad_u,
                        const double                   kept,
                        const ArrayView<const double> &committed,
                        const ArrayView<double>       &trial,
                        Tensor<2, dim>                *d_kept,
                        const double                   hoop = 0.) const
      {
        if (!body.modified_volume())
          return body.model->evaluate(grad_u, committed, trial, hoop);
        const FBar<dim> f_bar(grad_u, kept, body.model->is_finite_strain());
        Response<dim>   weak;
        Tensor<2, dim>  unused;
        f_bar.weak_form(body.model->evaluate_3d(f_bar.modified_gradient(), committed, trial),
                        weak,
                        d_kept ? *d_kept : unused);
        return weak;
      }

      /**
       * @brief The projection of the volume change of @p body's cells: degree 0
       * for F-bar (one sample, the centre) and for mixed on Q1 and simplices,
       * degree 1 for mixed on Q2 (Q2/P1disc).
       */
      VolumeProjection<dim>
      volume_projection(const BodyMaterial<dim> &body) const
      {
        const bool p1 = body.volumetric == BodyMaterial<dim>::Volumetric::mixed &&
                        !body_mesh.simplex() && fe_pair->displacement_degree() == 2;
        return VolumeProjection<dim>(
            p1 ? 1 : 0, body_mesh.cell_gauss(1).point(0), body.model->is_finite_strain());
      }

      /**
       * @brief F-bar and mixed: the gradient of @p u at the centre of every
       * cell this rank holds (owned and ghost) and the coefficients of its kept
       * volume change, for committed_response(); nothing when no material slot
       * asks for them (body_response.cc).
       */
      void
      compute_volume_fields(const TrilinosWrappers::MPI::Vector &u) const;

      /** @brief F-bar and mixed: the coefficients of the kept volume change of active cell @p
       * index (compute_volume_fields()). */
      const std::array<double, dim + 1> &
      kept_volume(const unsigned int index) const
      {
        return kept_volume_coefficients[index];
      }

    private:
      const BodyMesh<dim>                                &body_mesh;
      const QuadratureHistory                            &history;
      const std::unique_ptr<Discretization::FEPair<dim>> &fe_pair;
      const std::unique_ptr<FiniteElement<dim>>          &fe_u;
      const DoFHandler<dim>                              &dof_handler_u;
      const Quadrature<dim>                              &cell_quadrature;
      const bool                                          axisymmetric;

      /** the default model first, then the slots in use (BodyMesh::material_slot() of a body) */
      std::vector<BodyMaterial<dim>> materials;
      /** F-bar: ∇u at each cell's centre (by active index), of the last compute_volume_fields() */
      mutable std::vector<Tensor<2, dim>> centre_gradients;
      /** F-bar and mixed: the coefficients of each cell's kept volume change (by active index) */
      mutable std::vector<std::array<double, dim + 1>> kept_volume_coefficients;
    };
  } // namespace Materials
} // namespace StabilizedLagrangian
