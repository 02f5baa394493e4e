#pragma once

#include <deal.II/base/array_view.h>
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/numerics/rtree.h>

#include <stabilized_lagrangian/contact/partner.h>

#include <set>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    using namespace dealii;

    /**
     * @brief The master surface of a second deformable body (doc/formulation.md,
     * "Two deformable bodies"): the faces of the master boundary in their
     * deformed configuration, and the closest-point projection of slave points
     * onto them.
     *
     * Every rank holds the whole master surface (its reference geometry and
     * the global indices of its displacement DoFs), gathered once per mesh,
     * so a slave point is paired with its closest master face wherever that
     * face's cell lives; the deformed positions come from a vector whose
     * ghost set includes dofs(). Memory per rank is O(master faces). The
     * search runs on an R-tree of the deformed faces' bounding boxes.
     *
     * A face is described by its vertices (the reference map X(ξ) is
     * multilinear in them, as the cells' mapping) and by its displacement
     * nodes, ordered as the nodes of FE_Q<dim−1>(k), so x(ξ) = X(ξ) + Σ N_k(ξ) u_k.
     */
    template <int dim> class MasterSurface : public Partner<dim>
    {
    public:
      /**
       * @brief Collect the faces of @p dof_handler's mesh on the boundaries
       * @p boundary_ids from every rank (collective).
       */
      MasterSurface(const DoFHandler<dim>              &dof_handler,
                    const std::set<types::boundary_id> &boundary_ids,
                    const MPI_Comm                      communicator);

      /** @brief Number of master faces (on all ranks). */
      unsigned int
      n_faces() const
      {
        return face_sign.size();
      }

      /** @brief The displacement DoFs of the whole master surface (in the DoFHandler's numbering).
       */
      const IndexSet &
      dofs() const override
      {
        return surface_dofs;
      }

      /**
       * @brief Deform the surface by the displacement in @p u (its first block
       * numbered as the DoFHandler; ghosts must include dofs()) and rebuild the
       * search tree.
       */
      void
      update_configuration(const TrilinosWrappers::MPI::Vector &u) override;

      /**
       * @brief Closest point of the deformed surface to @p x, with the outward
       * normal there and the face and reference point of the pairing.
       */
      Pairing<dim>
      project(const Point<dim> &x) const override;

      /** @brief A meshed surface kinks at its vertices. */
      bool
      is_flat() const override
      {
        return false;
      }

      bool
      is_rigid() const override
      {
        return false;
      }

      /** @brief The pairing is not linearised: the solver pairs anew before each assembly. */
      bool
      has_pairing_derivatives() const override
      {
        return false;
      }

      Tensor<1, dim>
      follow(Pairing<dim>                        &pairing,
             const TrilinosWrappers::MPI::Vector &u,
             const TrilinosWrappers::MPI::Vector &step_start,
             const Point<dim> &) const override;

      /**
       * @brief The displacement DoFs of face @p face and their shape values at
       * @p xi: DoF dofs[i] moves the point by values[i] e_{components[i]}.
       */
      void
      shape_values(const Pairing<dim>                   &pairing,
                   std::vector<types::global_dof_index> &dofs,
                   std::vector<unsigned int>            &components,
                   std::vector<double>                  &values) const override;

      void
      shape_gradients(const Pairing<dim>              &pairing,
                      std::vector<Tensor<1, dim - 1>> &gradients) const override;
      /** @brief The displacement DoFs of face @p face (node-major, dim per node). */
      ArrayView<const types::global_dof_index>
      face_dof_indices(const unsigned int face) const override
      {
        return {face_dofs.data() + face * n_nodes * dim, n_nodes * dim};
      }

      ArrayView<const types::global_dof_index>
      pairing_dof_indices(const Pairing<dim> &pairing) const override
      {
        return face_dof_indices(pairing.master_face);
      }

      /**
       * @brief Deformed vertices of the faces whose boxes meet @p box (a vertex
       * shared by faces is listed once per face).
       */
      std::vector<Point<dim>>
      vertices_near(const BoundingBox<dim> &box) const override;

      unsigned int
      vertices_per_face() const override
      {
        return n_vertices;
      }

      /** @brief The faces sharing a node with the paired face, itself included. */
      const std::vector<unsigned int> &
      faces_near(const Pairing<dim> &pairing) const override
      {
        return face_neighbours[pairing.master_face];
      }

    private:
      /**
       * @brief Displacement of @p u at the reference point @p xi of face @p face.
       */
      Tensor<1, dim>
      displacement(const unsigned int                   face,
                   const Point<dim - 1>                &xi,
                   const TrilinosWrappers::MPI::Vector &u) const;

      /** @brief Reference position X(ξ) of @p xi on face @p face. */
      Point<dim>
      reference_point(const unsigned int face, const Point<dim - 1> &xi) const;
      /** Current position and the derivatives ∂x/∂ξ_a at @p xi on face @p face. */
      Point<dim>
      position(const unsigned int    face,
               const Point<dim - 1> &xi,
               Tensor<1, dim> (&dx)[dim - 1]) const;

      /** Outward unit normal from the derivatives ∂x/∂ξ_a of face @p face. */
      Tensor<1, dim>
      normal(const unsigned int face, const Tensor<1, dim> (&dx)[dim - 1]) const;

      static constexpr unsigned int n_vertices = GeometryInfo<dim>::vertices_per_face;

      FE_Q<dim - 1> node_element;
      unsigned int  n_nodes;
      /** per face: its vertices; its nodes' DoFs (node-major, dim per node); ±1 orienting the
       * normal */
      std::vector<Point<dim>>                face_vertices;
      std::vector<types::global_dof_index>   face_dofs;
      std::vector<double>                    face_sign;
      std::vector<std::vector<unsigned int>> face_neighbours;
      IndexSet                               surface_dofs;
      /** current node displacements (node-major per face) */
      std::vector<Tensor<1, dim>>                      node_displacements;
      RTree<std::pair<BoundingBox<dim>, unsigned int>> tree;
    };
  } // namespace Contact
} // namespace StabilizedLagrangian
