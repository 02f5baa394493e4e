#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/grid/reference_cell.h>

#include <stabilized_lagrangian/geometry/scene.h>
#include <stabilized_lagrangian/materials/material.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The bodies' mesh: the distributed triangulation built from the
   * scene's geometry (Geometry::Interface), its cell shape and quadratures,
   * and what the input names on it (boundaries and bodies by name or id).
   *
   * Hypercube meshes live on p4est's triangulation (adaptive refinement),
   * simplex meshes on the fully distributed one, built from a serial mesh
   * partitioned by METIS (p4est does not hold simplices; deal.II 9.4 cannot
   * refine the fully distributed one adaptively).
   */
  template <int dim> class BodyMesh
  {
  public:
    /** @brief Simplex meshes: the id of the local boundary faces that are not on the body's
     * boundary. */
    static constexpr types::boundary_id ghost_layer_boundary_id =
        numbers::internal_face_boundary_id - 1;

    /**
     * @brief An empty triangulation for the cells of @p geometry (which must
     * outlive this object); @p fe_pair_name (`Contact/Finite element pair`)
     * names the pair in the messages.
     */
    BodyMesh(const MPI_Comm                 &communicator,
             const Geometry::Interface<dim> &geometry,
             const std::string              &fe_pair_name);

    /** @brief The distributed triangulation. */
    parallel::DistributedTriangulationBase<dim> &
    triangulation()
    {
      return *storage;
    }

    /** @brief Whether the cells are triangles / tetrahedra. */
    bool
    simplex() const
    {
      return geometry.simplex_cells();
    }

    /** @brief The reference cell of the mesh's cells. */
    ReferenceCell
    cell_shape() const
    {
      return simplex() ? ReferenceCells::get_simplex<dim>() : ReferenceCells::get_hypercube<dim>();
    }

    /**
     * @brief The Gauss rule of the cells with @p n points per direction (QGauss on
     * hypercubes; on simplices QGaussSimplex, exact for the same degree 2n − 1).
     */
    Quadrature<dim>
    cell_gauss(const unsigned int n) const
    {
      return cell_shape().template get_gauss_type_quadrature<dim>(n);
    }

    /** @brief The Gauss rule of the faces with @p n points per direction. */
    Quadrature<dim - 1>
    face_gauss(const unsigned int n) const
    {
      return cell_shape().face_reference_cell(0).template get_gauss_type_quadrature<dim - 1>(n);
    }

    /**
     * @brief The rule whose points are the nodes of the contact faces for
     * degree @p degree: Gauss–Lobatto on lines and quadrilaterals; the
     * vertices (weight area/3) on triangles, where only degree 1 has positive
     * nodal weights.
     */
    Quadrature<dim - 1>
    face_nodes(const unsigned int degree) const;

    /**
     * @brief Build the geometry's mesh (the displacement's degree @p
     * displacement_degree: a locally refined simplex mesh with a quadratic
     * pair runs on one rank only).
     */
    void
    create(const unsigned int displacement_degree);

    /** @brief Refine every cell once (the inf-sup test's sequence of meshes). */
    void
    refine_globally(const unsigned int displacement_degree);

    /** @brief Axisymmetric model: refuse a mesh reaching x = r < 0. */
    void
    check_meridian_section();

    /** @brief Throw an InputError naming @p entry when the mesh has no boundary @p id. */
    void
    require_boundary(const types::boundary_id id, const std::string &entry) const;

    /**
     * @brief The id of the boundary named @p name (a Gmsh file's physical
     * group); throws an InputError naming @p entry when there is none.
     */
    types::boundary_id
    boundary_named(const std::string &name, const std::string &entry) const;

    /**
     * @brief Find the body of each `Material n/Bodies` entry of @p materials
     * (by name or material id) and give it that slot; throws an InputError
     * for a body the mesh does not have or one given twice.
     */
    void
    assign_material_slots(const std::vector<Materials::BodyMaterial<dim>> &materials);

    /** @brief The material slot of the body @p id (0: the default `Material`). */
    unsigned int
    material_slot(const types::material_id id) const
    {
      const auto slot = material_slots.find(id);
      return slot == material_slots.end() ? 0 : slot->second;
    }

  private:
    /**
     * Simplex meshes: build the geometry's mesh serially, refine it
     * `extra_refinements` more times, partition it (METIS) and give each rank
     * its share and a ghost layer.
     */
    void
    distribute_simplex_mesh(const unsigned int displacement_degree);
    /**
     * The boundary ids of the ghost cells' faces as their owners set them: a
     * geometry that sets ids from its cells' neighbourhood (close_contact_zone)
     * sees part of it from the ghost layer only, and every rank must agree
     * which faces are on Γc (the multiplier numbering counts on it).
     */
    void
    share_ghost_boundary_ids();

    MPI_Comm                                                     communicator;
    const Geometry::Interface<dim>                              &geometry;
    const std::string                                            fe_pair_name;
    std::unique_ptr<parallel::DistributedTriangulationBase<dim>> storage;
    /** simplex meshes: uniform refinements beyond the geometry's (refine_globally) */
    unsigned int extra_refinements = 0;
    /** a body's material slot, for the bodies a `Material n/Bodies` entry gives */
    std::map<types::material_id, unsigned int> material_slots;
  };
} // namespace StabilizedLagrangian
