// The scene checks of the rigid obstacle (solver/scene_checks.h): a body behind it or passing
// through it outside Γc, a motion the scene cannot follow, an axisymmetric model's obstacle
// that is no body of revolution.

#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <stabilized_lagrangian/solver/scene_checks.h>

#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <utility>

namespace StabilizedLagrangian
{
  template <int dim>
  void
  SceneChecks<dim>::warn_if_obstacle_not_of_revolution() const
  {
    if (!view.axisymmetric || !view.partner->is_rigid())
      return;
    Tensor<1, dim> axis;
    axis[1]                  = 1.;
    const std::string defect = view.obstacle.axisymmetry_defect(axis);
    if (!defect.empty())
      view.pcout << "WARNING: the obstacle is no body of revolution about the axis x = 0 of the "
                    "axisymmetric model (Geometry/Axisymmetric = true): "
                 << defect
                 << ". The model turns the obstacle's profile about the axis as it does the "
                    "body's section, so the body meets that solid of revolution. Put the "
                    "obstacle on the axis, or run the scene in 3D.\n";
  }

  template <int dim>
  void
  SceneChecks<dim>::warn_if_obstacle_motion_ignored() const
  {
    const bool two_bodies = !view.master_boundaries.empty();
    if (!two_bodies && !view.axisymmetric)
      return;
    // the motion sampled over the load path: its largest translation, and
    // its largest radial one (x₁ is the radius in an axisymmetric model)
    double translation = 0., radial = 0.;
    for (unsigned int k = 0; k <= 20; ++k)
      {
        const auto motion = view.obstacle_motion.at(k / 20. * view.load_stepping.end_time);
        translation       = std::max(translation, motion.translation.norm());
        radial            = std::max(radial, std::abs(motion.translation[0]));
      }
    if (two_bodies && (translation > 0. || view.obstacle_motion.rotates()))
      view.pcout << "WARNING: Obstacle/Motion moves the rigid obstacle, but this scene has two "
                    "deformable bodies (Contact/Master boundary ids) and no obstacle: the motion "
                    "is ignored. Move the second body by a Dirichlet condition on it (Boundary "
                    "conditions/Dirichlet <name>).\n";
    else if (!two_bodies && (radial > 0. || view.obstacle_motion.rotates()))
      view.pcout << "WARNING: Obstacle/Motion "
                 << (view.obstacle_motion.rotates() ? "turns the obstacle"
                                                    : "moves the obstacle radially")
                 << " in an axisymmetric model (Geometry/Axisymmetric), where the obstacle is a "
                    "body of revolution about the axis x = 0: it may only move along the axis. "
                    "The motion is applied to the obstacle's profile, which is no rigid motion of "
                    "the body of revolution.\n";
  }

  template <int dim>
  bool
  SceneChecks<dim>::warn_if_body_behind_obstacle() const
  {
    if (!view.partner->is_rigid())
      return false;
    // most of the body on the wrong side of the surface: the obstacle's normal
    // points into the body (g_n = (x − x̄)·n < 0 means penetration)
    const double tolerance = 1e-8 * GridTools::diameter(view.triangulation);
    unsigned int behind = 0, vertices = 0;
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            ++vertices;
            behind += view.partner->project(cell->vertex(v)).gap(cell->vertex(v)) < -tolerance;
          }
    behind   = Utilities::MPI::sum(behind, view.communicator);
    vertices = Utilities::MPI::sum(vertices, view.communicator);
    if (2 * behind > vertices)
      view.pcout
          << "WARNING: " << behind << " of " << vertices
          << " cell vertices lie behind the obstacle's surface (negative gap) before the first "
             "step. The obstacle's normal must point out of the obstacle, towards the body: "
             "check the `Obstacle` entries (a plane's Normal, for instance).\n";
    return 2 * behind > vertices;
  }

  namespace
  {
    /** The deepest reach of the obstacle into a boundary: the depth −g_n (mm) and where. */
    template <int dim> struct Reach
    {
      double     depth = 0.;
      Point<dim> where;

      /** Take the reach @p d at @p x if it is deeper. */
      void
      deepen(const double d, const Point<dim> &x)
      {
        if (d > depth)
          {
            depth = d;
            where = x;
          }
      }
    };

    /** The outward unit normal of the flat face through the vertices of boundary face @p f. */
    template <typename CellIterator>
    auto
    outward_normal(const CellIterator &cell, const unsigned int f)
    {
      constexpr int dim  = CellIterator::AccessorType::dimension;
      const auto    face = cell->face(f);
      // two edges from vertex 0 (a quadrilateral's 0–1 and 0–3, a triangle's 0–1 and 0–2)
      const Tensor<1, dim> a = face->vertex(1) - face->vertex(0);
      Tensor<1, dim>       normal;
      if constexpr (dim == 2)
        {
          normal[0] = a[1];
          normal[1] = -a[0];
        }
      else
        normal = cross_product_3d(a, face->vertex(face->n_vertices() - 1) - face->vertex(0));
      if (normal * (face->center() - cell->center()) < 0.)
        normal = -normal;
      return normal / normal.norm();
    }

    /**
     * Collective: the deepest of each rank's @p reach, by (boundary id,
     * moment: 0 before the first step, 1 at the end time).
     */
    template <int dim>
    std::map<std::pair<types::boundary_id, unsigned int>, Reach<dim>>
    deepest_over_ranks(
        const std::map<std::pair<types::boundary_id, unsigned int>, Reach<dim>> &reach,
        const MPI_Comm                                                           communicator)
    {
      std::vector<double> packed;
      for (const auto &[key, deepest] : reach)
        {
          packed.insert(packed.end(), {double(key.first), double(key.second), deepest.depth});
          for (unsigned int d = 0; d < dim; ++d)
            packed.push_back(deepest.where[d]);
        }
      std::map<std::pair<types::boundary_id, unsigned int>, Reach<dim>> all;
      for (const auto &rank : Utilities::MPI::all_gather(communicator, packed))
        for (std::size_t i = 0; i < rank.size(); i += 3 + dim)
          {
            Reach<dim> deepest;
            deepest.depth = rank[i + 2];
            for (unsigned int d = 0; d < dim; ++d)
              deepest.where[d] = rank[i + 3 + d];
            auto &entry = all[{types::boundary_id(rank[i]), unsigned(rank[i + 1])}];
            if (deepest.depth > entry.depth)
              entry = deepest;
          }
      return all;
    }
  } // namespace

  template <int dim>
  void
  SceneChecks<dim>::warn_if_body_passes_through_obstacle() const
  {
    if (!view.partner->is_rigid())
      return;
    const std::set<unsigned int> on_contact = contact_vertices();
    // the obstacle before the first step is the partner now; at the end time, x meets it as
    // the point the motion from the end back to the start takes x to meets it now
    const auto start = view.obstacle_motion.at(0.);
    const auto end   = view.obstacle_motion.at(view.load_stepping.end_time);
    const bool moves =
        (end.translation - start.translation).norm() > 0. || view.obstacle_motion.rotates();
    const auto depth = [&](const Point<dim> &x) { return -view.partner->project(x).gap(x); };
    double     smallest_face = std::numeric_limits<double>::max(), contact_depth_at_end = 0.;
    std::map<std::pair<types::boundary_id, unsigned int>, Reach<dim>> reach;
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const auto           face    = cell->face(f);
              const bool           contact = view.contact_boundaries.count(face->boundary_id()) > 0;
              const Tensor<1, dim> normal  = outward_normal(cell, f);
              smallest_face                = std::min(smallest_face, face->diameter());
              for (const unsigned int v : face->vertex_indices())
                {
                  const Point<dim> x = face->vertex(v), y = start.apply(end.inverse(x));
                  if (contact && moves)
                    contact_depth_at_end = std::max(contact_depth_at_end, depth(y));
                  if (contact || on_contact.count(face->vertex_index(v)) > 0)
                    continue;
                  reach[{face->boundary_id(), 0}].deepen(depth(x), x);
                  // at the end only a face that faces the obstacle: the contact pushes Γc
                  // back and its neighbours with it, but a face the obstacle meets head on
                  // ahead of Γc is not carried out of its way
                  const Tensor<1, dim> obstacle_normal =
                      end.rotation * transpose(start.rotation) * view.partner->project(y).normal;
                  if (moves && normal * obstacle_normal < -0.5)
                    reach[{face->boundary_id(), 1}].deepen(depth(y), x);
                }
            }
    // a reach below a thousandth of the smallest boundary face is round-off
    const double tolerance = 1e-3 * Utilities::MPI::min(smallest_face, view.communicator);
    contact_depth_at_end   = Utilities::MPI::max(contact_depth_at_end, view.communicator);
    // Hertz: the contact zone is where the rigid overlap reaches half the approach δ (a² = R δ
    // against the overlap's 2 R δ); a face off Γc reached deeper than half of Γc's reach at
    // the end would be in contact
    const double                 end_limit = std::max(tolerance, 0.5 * contact_depth_at_end);
    std::ostringstream           reached;
    std::set<types::boundary_id> boundaries;
    for (const auto &[key, deepest] : deepest_over_ranks(reach, view.communicator))
      if (deepest.depth > (key.second == 0 ? tolerance : end_limit))
        {
          boundaries.insert(key.first);
          reached << "\n  " << boundary_label(key.first) << ": " << deepest.depth << " mm deep at ("
                  << deepest.where << ") "
                  << (key.second == 0
                          ? "before the first step"
                          : "at the end time, with the obstacle where Obstacle/Motion takes it "
                            "and the body undeformed (its deformation is not known before the "
                            "run): deeper than half the obstacle's reach into the contact "
                            "surface, so it would be in contact");
        }
    if (!boundaries.empty())
      report_pass_through(boundaries, reached.str());
  }

  template <int dim>
  std::set<unsigned int>
  SceneChecks<dim>::contact_vertices() const
  {
    // (a vertex shared with a Γc face of another rank's cell is on Γc too)
    std::set<unsigned int> vertices;
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              view.contact_boundaries.count(cell->face(f)->boundary_id()) > 0)
            for (const unsigned int v : cell->face(f)->vertex_indices())
              vertices.insert(cell->face(f)->vertex_index(v));
    return vertices;
  }

  template <int dim>
  void
  SceneChecks<dim>::report_pass_through(const std::set<types::boundary_id> &boundaries,
                                        const std::string                  &reached) const
  {
    std::string contact_ids, zone_hint;
    for (const auto id : view.contact_boundaries)
      contact_ids += (contact_ids.empty() ? "" : ", ") + std::to_string(id);
    for (const auto &zone : view.geometry.contact_zones())
      if (boundaries.count(zone.outside_id) > 0 && view.contact_boundaries.count(zone.id) > 0)
        zone_hint = ", or raise " + zone.entry;
    view.pcout << "WARNING: the obstacle reaches into the body outside its contact surface "
                  "(Contact/Contact boundary ids = "
               << contact_ids
               << "), where nothing keeps it out: the body passes through the obstacle there."
               << reached << "\nAdd those boundaries to Contact/Contact boundary ids" << zone_hint
               << ", or place the body or the obstacle (the Obstacle entries, Obstacle/Motion) "
                  "so that only the contact surface meets it.\n";
  }

  template <int dim>
  std::string
  SceneChecks<dim>::boundary_label(const types::boundary_id id) const
  {
    for (const auto &[name, boundary_id] : view.geometry.boundary_names())
      if (boundary_id == id)
        return "boundary '" + name + "' (id " + std::to_string(id) + ")";
    return "boundary " + std::to_string(id);
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated in scene_checks.cc).
#define SL_INSTANTIATE(dim)                                                   \
  template void SceneChecks<dim>::warn_if_obstacle_not_of_revolution() const; \
  template void SceneChecks<dim>::warn_if_obstacle_motion_ignored() const;    \
  template bool SceneChecks<dim>::warn_if_body_behind_obstacle() const;       \
  template void SceneChecks<dim>::warn_if_body_passes_through_obstacle() const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
