// The contact search on the master surface (doc/formulation.md, "Distributed
// contact search"): the faces a rank gathers from their owners, the R-tree of
// the held faces' deformed bounding boxes, and the closest-point projection of
// a slave point onto them. The faces themselves (their geometry, DoFs and
// linearisation) are in master_surface.cc.

#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/contact/master_surface.h>

#include <algorithm>
#include <limits>
#include <map>
#include <set>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    namespace
    {
      /** True when the boxes @p a and @p b share a point. */
      template <int dim>
      bool
      boxes_meet(const BoundingBox<dim> &a, const BoundingBox<dim> &b)
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (a.lower_bound(d) > b.upper_bound(d) || b.lower_bound(d) > a.upper_bound(d))
            return false;
        return true;
      }

      /** Squared distance from @p x to the box @p box (0 inside). */
      template <int dim>
      double
      squared_distance(const BoundingBox<dim> &box, const Point<dim> &x)
      {
        const auto &[low, high] = box.get_boundary_points();
        double result           = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          result += Utilities::fixed_power<2>(std::max({0., low[d] - x[d], x[d] - high[d]}));
        return result;
      }
    } // namespace

    template <int dim>
    bool
    MasterSurface<dim>::gather_faces_near(const std::vector<BoundingBox<dim>> &region,
                                          const TrilinosWrappers::MPI::Vector *u)
    {
      if (replicated)
        return false;
      // every rank's slave region, 2 d around
      std::vector<double> corners;
      for (const auto &box : region)
        for (const Point<dim> &corner :
             {box.get_boundary_points().first, box.get_boundary_points().second})
          for (unsigned int d = 0; d < dim; ++d)
            corners.push_back(corner[d]);
      std::vector<std::pair<BoundingBox<dim>, unsigned int>> regions;
      const auto all_corners = Utilities::MPI::all_gather(communicator, corners);
      for (unsigned int rank = 0; rank < all_corners.size(); ++rank)
        for (unsigned int b = 0; b < all_corners[rank].size(); b += 2 * dim)
          {
            Point<dim> low, high;
            for (unsigned int d = 0; d < dim; ++d)
              {
                low[d]  = all_corners[rank][b + d];
                high[d] = all_corners[rank][b + dim + d];
              }
            BoundingBox<dim> box({low, high});
            box.extend(2. * search_distance);
            regions.emplace_back(box, rank);
          }
      const auto region_tree = pack_rtree(regions);

      // this rank's faces to every rank whose region they meet
      namespace bgi = boost::geometry::index;
      std::map<unsigned int, std::vector<FaceRecord>> to_ranks;
      for (FaceRecord &record : owned_faces)
        {
          record.box = deformed_box(record, u);
          std::vector<std::pair<BoundingBox<dim>, unsigned int>> hits;
          region_tree.query(bgi::intersects(record.box), std::back_inserter(hits));
          std::set<unsigned int> ranks;
          for (const auto &hit : hits)
            ranks.insert(hit.second);
          for (const unsigned int rank : ranks)
            to_ranks[rank].push_back(record);
        }
      std::map<unsigned int, PackedFaces> to_send;
      for (const auto &[rank, records] : to_ranks)
        to_send[rank] = pack(records);

      // a face within d of the region that is not held yet: take all those within 2 d
      std::vector<FaceRecord> fresh;
      bool                    missing = false;
      for (const auto &[rank, packed] : Utilities::MPI::some_to_some(communicator, to_send))
        for (const FaceRecord &record : unpack(packed))
          if (slots.count(record.id) == 0)
            {
              fresh.push_back(record);
              for (BoundingBox<dim> box : region)
                {
                  box.extend(search_distance);
                  missing = missing || boxes_meet(box, record.box);
                }
            }
      if (missing)
        hold(fresh);
      return Utilities::MPI::logical_or(missing, communicator);
    }

    template <int dim>
    void
    MasterSurface<dim>::update_configuration(const TrilinosWrappers::MPI::Vector &u)
    {
      std::vector<std::pair<BoundingBox<dim>, unsigned int>> boxes;
      boxes.reserve(face_ids.size());
      const std::vector<Point<dim - 1>> &node_points = node_element.get_unit_support_points();
      for (unsigned int f = 0; f < face_ids.size(); ++f)
        {
          std::vector<Point<dim>> points;
          for (unsigned int k = 0; k < n_nodes; ++k)
            {
              Tensor<1, dim> &u_k = node_displacements[f * n_nodes + k];
              for (unsigned int d = 0; d < dim; ++d)
                u_k[d] = u(face_dofs[(f * n_nodes + k) * dim + d]);
              points.push_back(reference_point(f, node_points[k]) + u_k);
            }
          boxes.emplace_back(padded_box(points), f);
        }
      tree = pack_rtree(boxes);
    }

    template <int dim>
    Pairing<dim>
    MasterSurface<dim>::project(const Point<dim> &x) const
    {
      namespace bgi = boost::geometry::index;
      if (face_ids.empty())
        {
          // no master face within the search distance: an open pairing that far
          Pairing<dim> pairing;
          pairing.normal[dim - 1] = 1.;
          pairing.master_point    = x - search_distance * pairing.normal;
          pairing.tangents        = tangent_basis(pairing.normal);
          return pairing;
        }
      double         best_distance = std::numeric_limits<double>::max();
      unsigned int   best_face     = 0;
      Point<dim - 1> best_xi;
      // candidates by increasing distance to their boxes, until no box is
      // closer than the best projection found
      for (auto it = tree.qbegin(bgi::nearest(x, n_held_faces())); it != tree.qend(); ++it)
        {
          if (std::sqrt(squared_distance(it->first, x)) > best_distance)
            break;
          const unsigned int   face = it->second;
          Tensor<1, dim>       dx[dim - 1];
          const Point<dim - 1> xi       = closest_point_on_face(face, x);
          const double         distance = position(face, xi, dx).distance(x);
          // ties (a shared vertex or edge) to the smaller id, whatever the order faces are held
          // in
          if (distance < best_distance ||
              (distance == best_distance && face_ids[face] < face_ids[best_face]))
            {
              best_distance = distance;
              best_face     = face;
              best_xi       = xi;
            }
        }
      Pairing<dim>   pairing;
      Tensor<1, dim> dx[dim - 1];
      pairing.master_point           = position(best_face, best_xi, dx);
      pairing.normal                 = normal(best_face, dx);
      pairing.tangents               = tangent_basis(pairing.normal);
      pairing.master_face            = static_cast<int>(face_ids[best_face]);
      pairing.master_reference_point = best_xi;
      return pairing;
    }

    template <int dim>
    Point<dim - 1>
    MasterSurface<dim>::closest_point_on_face(const unsigned int face, const Point<dim> &x) const
    {
      Point<dim - 1> xi;
      for (unsigned int a = 0; a < dim - 1; ++a)
        xi[a] = 0.5;
      // Gauss–Newton on |x(ξ) − x|², ξ kept in the reference face
      Tensor<1, dim> dx[dim - 1];
      for (unsigned int iteration = 0; iteration < 50; ++iteration)
        {
          const Tensor<1, dim> r = position(face, xi, dx) - x;
          Tensor<2, dim - 1>   JtJ;
          Tensor<1, dim - 1>   Jtr;
          for (unsigned int a = 0; a < dim - 1; ++a)
            {
              Jtr[a] = dx[a] * r;
              for (unsigned int b = 0; b < dim - 1; ++b)
                JtJ[a][b] = dx[a] * dx[b];
            }
          Tensor<1, dim - 1> step = -(invert(JtJ) * Jtr);
          // A coordinate at the face's edge whose step leaves the face is
          // held there and the others minimise along the edge (projected
          // Gauss–Newton): clamping the full step instead would stop where
          // τ_b·(x(ξ) − x) ≠ 0 on a face whose tangents are not orthogonal.
          bool held[dim - 1], any_held = false;
          for (unsigned int a = 0; a < dim - 1; ++a)
            {
              held[a] = (xi[a] <= 0. && step[a] < 0.) || (xi[a] >= 1. && step[a] > 0.);
              any_held |= held[a];
            }
          if (any_held)
            for (unsigned int a = 0; a < dim - 1; ++a)
              step[a] = held[a] ? 0. : -Jtr[a] / JtJ[a][a];
          Point<dim - 1> next = xi + step;
          for (unsigned int a = 0; a < dim - 1; ++a)
            next[a] = std::clamp(next[a], 0., 1.);
          const double change = next.distance(xi);
          xi                  = next;
          if (change < 1e-13)
            break;
        }
      return xi;
    }

    template <int dim>
    std::vector<Point<dim>>
    MasterSurface<dim>::vertices_near(const BoundingBox<dim> &box) const
    {
      namespace bgi = boost::geometry::index;
      std::vector<std::pair<BoundingBox<dim>, unsigned int>> hits;
      tree.query(bgi::intersects(box), std::back_inserter(hits));
      std::vector<Point<dim>> vertices;
      Tensor<1, dim>          dx[dim - 1];
      for (const auto &hit : hits)
        for (unsigned int v = 0; v < n_vertices; ++v)
          {
            Point<dim - 1> corner;
            for (unsigned int a = 0; a < dim - 1; ++a)
              corner[a] = (v >> a) & 1;
            vertices.push_back(position(hit.second, corner, dx));
          }
      return vertices;
    }

    // Explicit instantiation of the members defined in this file (the class
    // itself is instantiated in master_surface.cc).
#define SL_INSTANTIATE(dim)                                                                             \
  template bool MasterSurface<dim>::gather_faces_near(const std::vector<BoundingBox<dim>> &,            \
                                                      const TrilinosWrappers::MPI::Vector *);           \
  template void MasterSurface<dim>::update_configuration(const TrilinosWrappers::MPI::Vector &);        \
  template Pairing<dim>            MasterSurface<dim>::project(const Point<dim> &) const;               \
  template Point<dim - 1>          MasterSurface<dim>::closest_point_on_face(unsigned int,              \
                                                                    const Point<dim> &) const; \
  template std::vector<Point<dim>> MasterSurface<dim>::vertices_near(const BoundingBox<dim> &)          \
      const;

    SL_INSTANTIATE(2)
    SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
  } // namespace Contact
} // namespace StabilizedLagrangian
