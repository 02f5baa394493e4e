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

#include <map>
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
     * Each rank owns the master faces of its own cells. A slave point must be
     * paired with its closest master face wherever that face's cell lives, so
     * a rank holds copies of the faces it may be paired with (their reference
     * geometry and the global indices of their displacement DoFs); the deformed
     * positions come from a vector whose ghost set includes dofs(). Which faces
     * a rank holds (doc/formulation.md, "Distributed contact search"):
     * - distributed (the default): the faces whose deformed bounding boxes
     *   come within the search distance d of this rank's slave faces, gathered
     *   by gather_faces_near() from their owners with one exchange of the
     *   ranks' slave regions (a few boxes each) and point-to-point messages;
     *   when a needed face is missing, the rank takes all those within 2 d, so
     *   that the set, and the ghosts that follow it, grow seldom. A rank never
     *   drops a face before the mesh changes. Memory per rank: this rank's
     *   share plus the master faces near its slave faces;
     * - replicated: every rank holds every face, gathered once per mesh
     *   (memory per rank O(all master faces)), the reference to compare with.
     * The closest point within d of a slave face is among the held faces, so
     * both give the same pairings there; a slave point further than d from
     * every held face is far from contact and paired with the nearest held
     * face, or with none (an open pairing d away, without DoFs).
     *
     * The search runs on an R-tree of the held faces' deformed bounding boxes.
     * Faces are named by global ids (their owner's offset plus their place
     * among its faces), the same on every rank.
     *
     * A face is described by its vertices (the reference map X(ξ) is
     * multilinear in them, as the cells' mapping) and by its displacement
     * nodes, ordered as the nodes of FE_Q<dim−1>(k), so x(ξ) = X(ξ) + Σ N_k(ξ) u_k.
     */
    template <int dim> class MasterSurface : public Partner<dim>
    {
    public:
      /**
       * @brief Collect this rank's faces of @p dof_handler's mesh on the
       * boundaries @p boundary_ids (collective); with @p replicated, every
       * rank takes every rank's faces at once. @p search_distance: d > 0.
       */
      MasterSurface(const DoFHandler<dim>              &dof_handler,
                    const std::set<types::boundary_id> &boundary_ids,
                    const MPI_Comm                      communicator,
                    const bool                          replicated,
                    const double                        search_distance);

      /** @brief Number of master faces (on all ranks). */
      unsigned int
      n_faces() const override
      {
        return n_global_faces;
      }

      /** @brief Number of master faces this rank holds. */
      unsigned int
      n_held_faces() const override
      {
        return face_ids.size();
      }

      /** @brief The displacement DoFs of the faces this rank holds (in the DoFHandler's numbering).
       */
      const IndexSet &
      dofs() const override
      {
        return surface_dofs;
      }

      bool
      gather_faces_near(const std::vector<BoundingBox<dim>> &region,
                        const TrilinosWrappers::MPI::Vector *u) override;

      /**
       * @brief Deform the held faces by the displacement in @p u (its first
       * block numbered as the DoFHandler; ghosts must include dofs()) and
       * rebuild the search tree.
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
       * @brief The displacement DoFs of the pairing's face and their shape
       * values at its ξ: DoF dofs[i] moves the point by values[i] e_{components[i]}.
       */
      void
      shape_values(const Pairing<dim>                   &pairing,
                   std::vector<types::global_dof_index> &dofs,
                   std::vector<unsigned int>            &components,
                   std::vector<double>                  &values) const override;

      void
      shape_gradients(const Pairing<dim>              &pairing,
                      std::vector<Tensor<1, dim - 1>> &gradients) const override;
      /** @brief The displacement DoFs of the held face with global id @p face (node-major, dim per
       * node). */
      ArrayView<const types::global_dof_index>
      face_dof_indices(const unsigned int face) const override;

      ArrayView<const types::global_dof_index>
      pairing_dof_indices(const Pairing<dim> &pairing) const override
      {
        if (pairing.master_face < 0)
          return {};
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

      /** @brief The held faces sharing a node with the paired face, itself included (global ids).
       */
      const std::vector<unsigned int> &
      faces_near(const Pairing<dim> &pairing) const override;

    private:
      /** A face as its owner describes it to the ranks that hold a copy. */
      struct FaceRecord
      {
        unsigned int                         id;
        std::vector<Point<dim>>              vertices;
        double                               sign;
        std::vector<types::global_dof_index> dofs;
        /** in transit: its deformed bounding box */
        BoundingBox<dim> box;
      };

      /** Faces packed for a message: their geometry and boxes, their ids and DoFs. */
      using PackedFaces = std::pair<std::vector<double>, std::vector<types::global_dof_index>>;

      PackedFaces
      pack(const std::vector<FaceRecord> &records) const;

      std::vector<FaceRecord>
      unpack(const PackedFaces &packed) const;

      /**
       * @brief This rank's faces of @p dof_handler's mesh on the boundaries
       * @p boundary_ids, into owned_faces: their vertices, their DoFs
       * (node-major) and the sign that orients their normal outward.
       */
      void
      collect_owned_faces(const DoFHandler<dim>              &dof_handler,
                          const std::set<types::boundary_id> &boundary_ids);

      /**
       * @brief Number the faces globally (collective): the owner's offset
       * plus the place among its faces, the same on every rank.
       */
      void
      number_owned_faces();

      /** @brief Hold the faces @p records (not held yet), and index all held faces anew. */
      void
      hold(const std::vector<FaceRecord> &records);

      /** @brief Where the held face with global id @p face is stored. */
      unsigned int
      slot(const unsigned int face) const;

      /**
       * @brief Bounding box of the face @p record displaced by @p u at its
       * nodes (null: undisplaced), with room for the curvature of
       * higher-order faces between their nodes.
       */
      BoundingBox<dim>
      deformed_box(const FaceRecord &record, const TrilinosWrappers::MPI::Vector *u) const;

      /**
       * @brief Displacement of @p u at the reference point @p xi of held face @p face.
       */
      Tensor<1, dim>
      displacement(const unsigned int                   face,
                   const Point<dim - 1>                &xi,
                   const TrilinosWrappers::MPI::Vector &u) const;

      /** @brief Reference position X(ξ) of @p xi on held face @p face. */
      Point<dim>
      reference_point(const unsigned int face, const Point<dim - 1> &xi) const;
      /** Current position and the derivatives ∂x/∂ξ_a at @p xi on held face @p face. */
      Point<dim>
      position(const unsigned int    face,
               const Point<dim - 1> &xi,
               Tensor<1, dim> (&dx)[dim - 1]) const;

      /**
       * @brief The reference point ξ of held face @p face closest to @p x in
       * the deformed configuration: projected Gauss–Newton on |x(ξ) − x|²,
       * ξ kept in the reference face.
       */
      Point<dim - 1>
      closest_point_on_face(const unsigned int face, const Point<dim> &x) const;

      /**
       * @brief The bounding box of a face's nodes @p points, with room for
       * the curvature of higher-order faces between their nodes.
       */
      static BoundingBox<dim>
      padded_box(const std::vector<Point<dim>> &points);

      /** Outward unit normal from the derivatives ∂x/∂ξ_a of held face @p face. */
      Tensor<1, dim>
      normal(const unsigned int face, const Tensor<1, dim> (&dx)[dim - 1]) const;

      static constexpr unsigned int n_vertices = GeometryInfo<dim>::vertices_per_face;

      MPI_Comm      communicator;
      bool          replicated;
      double        search_distance;
      FE_Q<dim - 1> node_element;
      unsigned int  n_nodes;
      unsigned int  n_global_faces;
      /** this rank's own faces */
      std::vector<FaceRecord> owned_faces;
      /** per held face (by slot): its global id; its vertices; its nodes' DoFs
       * (node-major, dim per node); ±1 orienting the normal; the held faces
       * sharing a node with it (global ids) */
      std::vector<unsigned int>              face_ids;
      std::map<unsigned int, unsigned int>   slots;
      std::vector<Point<dim>>                face_vertices;
      std::vector<types::global_dof_index>   face_dofs;
      std::vector<double>                    face_sign;
      std::vector<std::vector<unsigned int>> face_neighbours;
      IndexSet                               surface_dofs;
      const std::vector<unsigned int>        no_faces;
      /** current node displacements (node-major per held face) */
      std::vector<Tensor<1, dim>>                      node_displacements;
      RTree<std::pair<BoundingBox<dim>, unsigned int>> tree;
    };
  } // namespace Contact
} // namespace StabilizedLagrangian
