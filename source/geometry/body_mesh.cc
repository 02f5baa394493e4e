#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <stabilized_lagrangian/geometry/body_mesh.h>
#include <stabilized_lagrangian/parameters.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace
  {
    /**
     * The triangulation for the geometry's cells: p4est's for hypercubes
     * (adaptive refinement), the fully distributed one for simplices (p4est
     * does not hold them; deal.II 9.4 cannot refine it adaptively).
     */
    template <int dim>
    std::unique_ptr<parallel::DistributedTriangulationBase<dim>>
    new_triangulation(const MPI_Comm &communicator, const bool simplex)
    {
      if (simplex)
        return std::make_unique<parallel::fullydistributed::Triangulation<dim>>(communicator);
      return std::make_unique<parallel::distributed::Triangulation<dim>>(
          communicator,
          typename Triangulation<dim>::MeshSmoothing(
              Triangulation<dim>::limit_level_difference_at_vertices));
    }

    std::string
    list_ids(const std::set<types::boundary_id> &ids)
    {
      std::string result;
      for (const auto id : ids)
        result += (result.empty() ? "" : ", ") + std::to_string(id);
      return result;
    }

    /**
     * Refuse a coarse cell that is inverted (its vertices ordered the other
     * way round: a negative Jacobian), self-intersecting (a bow-tie, whose
     * Jacobian changes sign over it) or degenerate (no volume): such a cell
     * gives a wrong or singular system, found only as a Newton iteration
     * that does not converge. The Jacobian of the cell's linear mapping is
     * checked at the 2^dim Gauss points of a hypercube (a corner's may vanish
     * or turn negative on a usable cell: an edge collapsed on the axis of a
     * meshed cylinder); a simplex's is constant, and deal.II maps either
     * orientation, so only its size counts.
     */
    template <int dim>
    void
    check_cell_orientation(const Triangulation<dim> &triangulation)
    {
      // one FEValues per kind of cell: its default linear mapping and Gauss points
      std::map<ReferenceCell, std::pair<FE_Nothing<dim>, std::unique_ptr<FEValues<dim>>>> kinds;
      for (const auto &cell : triangulation.cell_iterators_on_level(0))
        {
          const ReferenceCell kind  = cell->reference_cell();
          auto                found = kinds.find(kind);
          if (found == kinds.end())
            {
              found = kinds.emplace(kind, std::make_pair(FE_Nothing<dim>(kind), nullptr)).first;
              found->second.second =
                  std::make_unique<FEValues<dim>>(kind.template get_default_linear_mapping<dim>(),
                                                  found->second.first,
                                                  kind.template get_gauss_type_quadrature<dim>(2),
                                                  update_jacobians);
            }
          FEValues<dim> &fe_values = *found->second.second;
          fe_values.reinit(cell);
          const bool   simplex  = kind.is_simplex();
          const double scale    = std::pow(cell->diameter(), dim);
          double       smallest = std::numeric_limits<double>::max(), largest = -smallest;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const double det = determinant(Tensor<2, dim>(fe_values.jacobian(q))) / scale;
              smallest         = std::min(smallest, simplex ? std::abs(det) : det);
              largest          = std::max(largest, simplex ? std::abs(det) : det);
            }
          if (smallest > 1e-10)
            continue;
          std::ostringstream message;
          message << "Geometry: the cell of the mesh at (" << cell->center() << ") is "
                  << (largest < 0.    ? "inverted: its vertices are ordered the other way round (a "
                                        "negative Jacobian; Gmsh reports such cells as 'jac. < 0')"
                      : smallest < 0. ? "self-intersecting (a bow-tie): its Jacobian changes sign "
                                        "over it"
                                      : "degenerate: it has no volume")
                  << ". The run would solve a wrong or singular system. Fix the mesh (in Gmsh: "
                     "the orientation of the surface or volume, Mesh.Optimize) and run again.";
          throw InputError(message.str());
        }
    }

    /**
     * Why the contact zone @p zone holds no face of @p triangulation (its
     * radius is below the distance of the nearest face centre from its
     * centre), and what to do, for the message of @p entry = @p id.
     */
    template <int dim>
    std::string
    empty_zone_message(const Triangulation<dim>                             &triangulation,
                       const MPI_Comm                                        communicator,
                       const typename Geometry::Interface<dim>::ContactZone &zone,
                       const std::string                                    &entry)
    {
      // the curved faces outside the zone: the nearest centre and the size of the faces there
      double nearest = std::numeric_limits<double>::max();
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == zone.outside_id)
              nearest = std::min(nearest, face->center().distance(zone.centre));
      nearest     = Utilities::MPI::min(nearest, communicator);
      double size = 0.;
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == zone.outside_id &&
                face->center().distance(zone.centre) <= nearest * (1. + 1e-12))
              size = std::max(size, face->diameter());
      size                       = Utilities::MPI::max(size, communicator);
      const std::string  section = zone.entry.substr(0, zone.entry.rfind('/'));
      std::ostringstream message;
      message << entry << " = " << zone.id << ": the contact zone holds no face of the mesh. "
              << zone.entry << " = " << zone.radius
              << " mm takes the curved faces whose centre lies within " << zone.radius
              << " mm of the contact point (" << zone.centre << "), and on this mesh the nearest "
              << "face centre is " << nearest << " mm from it (faces of " << size
              << " mm there). Raise " << zone.entry << " above " << nearest
              << " mm, or refine the mesh near the contact point (" << section
              << "/Global refinements, Local refinements).";
      return message.str();
    }
  } // namespace

  template <int dim>
  BodyMesh<dim>::BodyMesh(const MPI_Comm                 &communicator,
                          const Geometry::Interface<dim> &geometry,
                          const std::string              &fe_pair_name)
      : communicator(communicator)
      , geometry(geometry)
      , fe_pair_name(fe_pair_name)
      , storage(new_triangulation<dim>(communicator, geometry.simplex_cells()))
  {
  }

  template <int dim>
  Quadrature<dim - 1>
  BodyMesh<dim>::face_nodes(const unsigned int degree) const
  {
    if (!simplex() || dim == 2)
      return QGaussLobatto<dim - 1>(degree + 1);
    if (degree > 1)
      throw InputError("Contact/Contact quadrature = Gauss-Lobatto needs degree 1 on tetrahedra "
                       "(P1/P1): the quadratic nodal weights of a triangle vanish at its "
                       "vertices. Use Contact quadrature = Gauss with " +
                       fe_pair_name + ".");
    std::vector<Point<dim - 1>> vertices;
    for (const unsigned int v : ReferenceCells::get_simplex<dim - 1>().vertex_indices())
      vertices.push_back(ReferenceCells::get_simplex<dim - 1>().template vertex<dim - 1>(v));
    return Quadrature<dim - 1>(vertices, std::vector<double>(vertices.size(), 1. / 6.));
  }

  template <int dim>
  void
  BodyMesh<dim>::create(const unsigned int displacement_degree)
  {
    if (simplex())
      distribute_simplex_mesh(displacement_degree);
    else
      {
        geometry.create_mesh(*storage);
        check_cell_orientation(*storage);
        share_ghost_boundary_ids();
      }
  }

  template <int dim>
  void
  BodyMesh<dim>::distribute_simplex_mesh(const unsigned int displacement_degree)
  {
    Triangulation<dim> serial;
    geometry.create_mesh(serial);
    check_cell_orientation(serial);
    serial.refine_global(extra_refinements);
    if (serial.has_hanging_nodes() && displacement_degree > 1 &&
        Utilities::MPI::n_mpi_processes(communicator) > 1)
      throw InputError(
          "Geometry: a locally refined simplex mesh with the quadratic pair " + fe_pair_name +
          " runs on one MPI rank only: deal.II 9.4 cannot constrain the hanging nodes of P2 "
          "next to another rank's cells. Use P1/P1, one rank, or uniform refinement only "
          "(Local refinements = 0).");
    // METIS is deterministic: the same ranks get the same cells in every run (restart)
    GridTools::partition_triangulation(Utilities::MPI::n_mpi_processes(communicator), serial);
    const auto description =
        TriangulationDescription::Utilities::create_description_from_triangulation(serial,
                                                                                   communicator);
    auto &triangulation = *storage;
    triangulation.clear();
    for (const auto id : serial.get_manifold_ids())
      if (id != numbers::flat_manifold_id)
        triangulation.set_manifold(id, serial.get_manifold(id));
    triangulation.create_triangulation(description);
    // The faces between this rank's ghost layer and the cells it does not
    // hold are boundary faces of its local mesh, with the default id 0, a
    // user's id: move them to an id of their own, so that no boundary or
    // contact condition sees them.
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() &&
            !serial.create_cell_iterator(cell->id())->face(f)->at_boundary())
          cell->face(f)->set_boundary_id(ghost_layer_boundary_id);
  }

  template <int dim>
  void
  BodyMesh<dim>::refine_globally(const unsigned int displacement_degree)
  {
    if (simplex())
      {
        ++extra_refinements;
        distribute_simplex_mesh(displacement_degree);
      }
    else
      storage->refine_global(1);
  }

  template <int dim>
  void
  BodyMesh<dim>::share_ghost_boundary_ids()
  {
    using Ids = std::vector<types::boundary_id>;
    GridTools::exchange_cell_data_to_ghosts<Ids, Triangulation<dim>>(
        *storage,
        [](const typename Triangulation<dim>::active_cell_iterator &cell) -> std::optional<Ids> {
          Ids ids;
          for (const auto &face : cell->face_iterators())
            ids.push_back(face->at_boundary() ? face->boundary_id() : numbers::invalid_boundary_id);
          return ids;
        },
        [](const typename Triangulation<dim>::active_cell_iterator &cell, const Ids &ids) {
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              cell->face(f)->set_boundary_id(ids[f]);
        });
  }

  template <int dim>
  void
  BodyMesh<dim>::check_meridian_section()
  {
    double smallest_radius = std::numeric_limits<double>::max(), size = 0.;
    for (const auto &cell : storage->active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            smallest_radius = std::min(smallest_radius, cell->vertex(v)[0]);
            size            = std::max(size, cell->diameter());
          }
    smallest_radius = Utilities::MPI::min(smallest_radius, communicator);
    size            = Utilities::MPI::max(size, communicator);
    if (smallest_radius < -1e-10 * size)
      {
        std::ostringstream message;
        message << "Geometry/Axisymmetric = true: the mesh reaches x = " << smallest_radius
                << " mm, but x is the radius r >= 0 of the solid of revolution. Mesh only "
                   "the half x >= 0 of the section (Geometry/half ball/Symmetry planes = "
                   "true, or a Gmsh mesh of it).";
        throw InputError(message.str());
      }
  }

  template <int dim>
  void
  BodyMesh<dim>::require_boundary(const types::boundary_id id, const std::string &entry) const
  {
    // (a rank of a fully distributed mesh sees only the boundaries near its cells)
    std::set<types::boundary_id> mesh_ids;
    for (const auto mesh_id : storage->get_boundary_ids())
      if (mesh_id != ghost_layer_boundary_id)
        mesh_ids.insert(mesh_id);
    mesh_ids = Utilities::MPI::compute_set_union(mesh_ids, communicator);
    if (mesh_ids.count(id) > 0)
      return;
    for (const auto &zone : geometry.contact_zones())
      if (zone.id == id)
        throw InputError(empty_zone_message(*storage, communicator, zone, entry));
    throw InputError(entry + " = " + std::to_string(id) +
                     ": the mesh has no boundary with this id; it has " + list_ids(mesh_ids) + ".");
  }

  template <int dim>
  types::boundary_id
  BodyMesh<dim>::boundary_named(const std::string &name, const std::string &entry) const
  {
    const auto names = geometry.boundary_names();
    const auto found = names.find(name);
    if (found != names.end())
      return found->second;
    std::string groups;
    for (const auto &[group, id] : names)
      groups += (groups.empty() ? "" : ", ") + ("'" + group + "' (id " + std::to_string(id) + ")");
    std::string bodies;
    for (const auto &body : geometry.body_names())
      bodies += (bodies.empty() ? "" : ", ") + ("'" + body.first + "'");
    throw InputError(entry + " = '" + name + "': the mesh has no boundary of this name; " +
                     (names.empty() ? std::string("its boundaries have ids only")
                                    : "its boundaries are " + groups) +
                     (bodies.empty() ? "" : "; its bodies are " + bodies) + ".");
  }

  template <int dim>
  void
  BodyMesh<dim>::assign_material_slots(const std::vector<Materials::BodyMaterial<dim>> &materials)
  {
    // bodies of the material slots, by name (a Gmsh file's physical groups) or material id
    std::set<types::material_id> mesh_bodies;
    for (const auto &cell : storage->active_cell_iterators())
      if (cell->is_locally_owned())
        mesh_bodies.insert(cell->material_id());
    {
      std::set<types::material_id>          all_bodies;
      const std::vector<types::material_id> local(mesh_bodies.begin(), mesh_bodies.end());
      for (const auto &part : Utilities::MPI::all_gather(communicator, local))
        all_bodies.insert(part.begin(), part.end());
      mesh_bodies = all_bodies;
    }
    const auto body_names = geometry.body_names();
    material_slots.clear();
    for (unsigned int slot = 1; slot < materials.size(); ++slot)
      for (const auto &body : materials[slot].bodies)
        {
          const std::string  entry = materials[slot].slot + "/Bodies";
          types::material_id id    = numbers::invalid_material_id;
          const auto         named = body_names.find(body);
          if (named != body_names.end())
            id = named->second;
          else if (const auto number = StabilizedLagrangian::Parameters::decimal_integer(
                       body, numbers::invalid_material_id - 1))
            id = static_cast<types::material_id>(*number);
          if (id == numbers::invalid_material_id || mesh_bodies.count(id) == 0)
            {
              std::string known;
              for (const auto &[name, tag] : body_names)
                known += (known.empty() ? "" : ", ") +
                         ("'" + name + "' (id " + std::to_string(tag) + ")");
              for (const auto tag : mesh_bodies)
                known += (known.empty() ? "" : ", ") + ("id " + std::to_string(tag));
              throw InputError(entry + " = '" + body +
                               "': the mesh has no body of this name or "
                               "material id; its bodies are " +
                               known + ".");
            }
          if (material_slots.count(id) > 0)
            throw InputError(entry + " = '" + body + "': this body is already given the model of " +
                             materials[material_slots[id]].slot + ".");
          material_slots[id] = slot;
        }
  }

  template class BodyMesh<2>;
  template class BodyMesh<3>;
} // namespace StabilizedLagrangian
