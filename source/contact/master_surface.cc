#include <deal.II/base/exceptions.h>
#include <deal.II/base/geometry_info.h>

#include <deal.II/fe/fe.h>

#include <stabilized_lagrangian/contact/master_surface.h>

#include <limits>
#include <map>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    namespace
    {
      /** Multilinear weight of face vertex @p v (lexicographic) at @p xi, and its derivatives. */
      template <int dim>
      double
      vertex_weight(const unsigned int v, const Point<dim - 1> &xi, Tensor<1, dim - 1> &gradient)
      {
        double weight = 1.;
        for (unsigned int a = 0; a < dim - 1; ++a)
          gradient[a] = 1.;
        for (unsigned int d = 0; d < dim - 1; ++d)
          {
            const bool   upper  = (v >> d) & 1;
            const double factor = upper ? xi[d] : 1. - xi[d];
            weight *= factor;
            for (unsigned int a = 0; a < dim - 1; ++a)
              gradient[a] *= (a == d) ? (upper ? 1. : -1.) : factor;
          }
        return weight;
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
    MasterSurface<dim>::MasterSurface(const DoFHandler<dim>              &dof_handler,
                                      const std::set<types::boundary_id> &boundary_ids,
                                      const MPI_Comm                      communicator)
        : node_element(dof_handler.get_fe().degree)
        , n_nodes(node_element.n_dofs_per_cell())
        , surface_dofs(dof_handler.n_dofs())
    {
      const FiniteElement<dim> &fe = dof_handler.get_fe();
      // the node of FE_Q<dim−1> at each face DoF's support point
      const std::vector<Point<dim - 1>> &face_points = fe.get_unit_face_support_points();
      const std::vector<Point<dim - 1>> &node_points = node_element.get_unit_support_points();
      std::vector<unsigned int>          node_of(fe.n_dofs_per_face());
      for (unsigned int i = 0; i < node_of.size(); ++i)
        {
          node_of[i] = numbers::invalid_unsigned_int;
          for (unsigned int k = 0; k < n_nodes; ++k)
            if (face_points[i].distance(node_points[k]) < 1e-10)
              node_of[i] = k;
          AssertThrow(node_of[i] != numbers::invalid_unsigned_int, ExcInternalError());
        }

      // this rank's faces: vertices and sign, then the DoFs
      std::vector<double>                  local_geometry;
      std::vector<types::global_dof_index> local_dofs;
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_face());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                boundary_ids.count(cell->face(f)->boundary_id()) > 0)
              {
                const auto face = cell->face(f);
                face->get_dof_indices(dofs);
                std::vector<types::global_dof_index> ordered(n_nodes * dim);
                for (unsigned int i = 0; i < dofs.size(); ++i)
                  ordered[node_of[i] * dim + fe.face_system_to_component_index(i).first] = dofs[i];
                local_dofs.insert(local_dofs.end(), ordered.begin(), ordered.end());
                // the normal of the face's own parametrisation against the outward direction
                Point<dim - 1> centre;
                for (unsigned int a = 0; a < dim - 1; ++a)
                  centre[a] = 0.5;
                Tensor<1, dim> dX[dim - 1];
                for (unsigned int v = 0; v < n_vertices; ++v)
                  {
                    Tensor<1, dim - 1> gradient;
                    vertex_weight<dim>(v, centre, gradient);
                    for (unsigned int a = 0; a < dim - 1; ++a)
                      dX[a] += gradient[a] * face->vertex(v);
                    for (unsigned int d = 0; d < dim; ++d)
                      local_geometry.push_back(face->vertex(v)[d]);
                  }
                Tensor<1, dim> n;
                if constexpr (dim == 2)
                  n = Tensor<1, dim>({dX[0][1], -dX[0][0]});
                else
                  n = cross_product_3d(dX[0], dX[1]);
                local_geometry.push_back(n * (face->center() - cell->center()) > 0. ? 1. : -1.);
              }

      for (const auto &part : Utilities::MPI::all_gather(communicator, local_geometry))
        for (unsigned int r = 0; r < part.size(); r += n_vertices * dim + 1)
          {
            for (unsigned int v = 0; v < n_vertices; ++v)
              {
                Point<dim> vertex;
                for (unsigned int d = 0; d < dim; ++d)
                  vertex[d] = part[r + v * dim + d];
                face_vertices.push_back(vertex);
              }
            face_sign.push_back(part[r + n_vertices * dim]);
          }
      for (const auto &part : Utilities::MPI::all_gather(communicator, local_dofs))
        face_dofs.insert(face_dofs.end(), part.begin(), part.end());
      AssertThrow(face_dofs.size() == face_sign.size() * n_nodes * dim, ExcInternalError());
      for (const auto dof : face_dofs)
        surface_dofs.add_index(dof);
      surface_dofs.compress();

      // faces sharing a node
      std::map<types::global_dof_index, std::vector<unsigned int>> faces_at;
      for (unsigned int f = 0; f < n_faces(); ++f)
        for (unsigned int k = 0; k < n_nodes; ++k)
          faces_at[face_dofs[(f * n_nodes + k) * dim]].push_back(f);
      face_neighbours.resize(n_faces());
      for (unsigned int f = 0; f < n_faces(); ++f)
        {
          std::set<unsigned int> near;
          for (unsigned int k = 0; k < n_nodes; ++k)
            for (const unsigned int g : faces_at[face_dofs[(f * n_nodes + k) * dim]])
              near.insert(g);
          face_neighbours[f].assign(near.begin(), near.end());
        }
      node_displacements.assign(n_faces() * n_nodes, Tensor<1, dim>());
    }

    template <int dim>
    void
    MasterSurface<dim>::update_configuration(const TrilinosWrappers::MPI::Vector &u)
    {
      std::vector<std::pair<BoundingBox<dim>, unsigned int>> boxes;
      boxes.reserve(n_faces());
      const std::vector<Point<dim - 1>> &node_points = node_element.get_unit_support_points();
      for (unsigned int f = 0; f < n_faces(); ++f)
        {
          std::vector<Point<dim>> points;
          for (unsigned int k = 0; k < n_nodes; ++k)
            {
              Tensor<1, dim> &u_k = node_displacements[f * n_nodes + k];
              for (unsigned int d = 0; d < dim; ++d)
                u_k[d] = u(face_dofs[(f * n_nodes + k) * dim + d]);
              points.push_back(reference_point(f, node_points[k]) + u_k);
            }
          BoundingBox<dim> box(points);
          // room for the curvature of higher-order faces between their nodes
          const auto &[low, high] = box.get_boundary_points();
          box.extend(0.1 * low.distance(high));
          boxes.emplace_back(box, f);
        }
      tree = pack_rtree(boxes);
    }

    template <int dim>
    Point<dim>
    MasterSurface<dim>::reference_point(const unsigned int face, const Point<dim - 1> &xi) const
    {
      Point<dim> X;
      for (unsigned int v = 0; v < n_vertices; ++v)
        {
          Tensor<1, dim - 1> gradient;
          X += vertex_weight<dim>(v, xi, gradient) * face_vertices[face * n_vertices + v];
        }
      return X;
    }

    template <int dim>
    Point<dim>
    MasterSurface<dim>::position(const unsigned int    face,
                                 const Point<dim - 1> &xi,
                                 Tensor<1, dim> (&dx)[dim - 1]) const
    {
      Point<dim> x;
      for (unsigned int a = 0; a < dim - 1; ++a)
        dx[a] = Tensor<1, dim>();
      for (unsigned int v = 0; v < n_vertices; ++v)
        {
          Tensor<1, dim - 1> gradient;
          const Point<dim>  &vertex = face_vertices[face * n_vertices + v];
          x += vertex_weight<dim>(v, xi, gradient) * vertex;
          for (unsigned int a = 0; a < dim - 1; ++a)
            dx[a] += gradient[a] * vertex;
        }
      for (unsigned int k = 0; k < n_nodes; ++k)
        {
          const Tensor<1, dim>     &u_k      = node_displacements[face * n_nodes + k];
          const Tensor<1, dim - 1> &gradient = node_element.shape_grad(k, xi);
          x += node_element.shape_value(k, xi) * u_k;
          for (unsigned int a = 0; a < dim - 1; ++a)
            dx[a] += gradient[a] * u_k;
        }
      return x;
    }

    template <int dim>
    Tensor<1, dim>
    MasterSurface<dim>::normal(const unsigned int face, const Tensor<1, dim> (&dx)[dim - 1]) const
    {
      Tensor<1, dim> n;
      if constexpr (dim == 2)
        n = Tensor<1, dim>({dx[0][1], -dx[0][0]});
      else
        n = cross_product_3d(dx[0], dx[1]);
      return face_sign[face] * n / n.norm();
    }

    template <int dim>
    Pairing<dim>
    MasterSurface<dim>::project(const Point<dim> &x) const
    {
      namespace bgi                = boost::geometry::index;
      double         best_distance = std::numeric_limits<double>::max();
      unsigned int   best_face     = 0;
      Point<dim - 1> best_xi;
      // candidates by increasing distance to their boxes, until no box is
      // closer than the best projection found
      for (auto it = tree.qbegin(bgi::nearest(x, n_faces())); it != tree.qend(); ++it)
        {
          if (std::sqrt(squared_distance(it->first, x)) > best_distance)
            break;
          const unsigned int face = it->second;
          Point<dim - 1>     xi;
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
              const Tensor<1, dim - 1> step = -(invert(JtJ) * Jtr);
              Point<dim - 1>           next = xi + step;
              for (unsigned int a = 0; a < dim - 1; ++a)
                next[a] = std::clamp(next[a], 0., 1.);
              const double change = next.distance(xi);
              xi                  = next;
              if (change < 1e-13)
                break;
            }
          const double distance = position(face, xi, dx).distance(x);
          if (distance < best_distance)
            {
              best_distance = distance;
              best_face     = face;
              best_xi       = xi;
            }
        }
      AssertThrow(best_distance < std::numeric_limits<double>::max(),
                  ExcMessage("the master surface has no faces"));

      Pairing<dim>   pairing;
      Tensor<1, dim> dx[dim - 1];
      pairing.master_point           = position(best_face, best_xi, dx);
      pairing.normal                 = normal(best_face, dx);
      pairing.tangents               = tangent_basis(pairing.normal);
      pairing.master_face            = static_cast<int>(best_face);
      pairing.master_reference_point = best_xi;
      return pairing;
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

    template <int dim>
    Tensor<1, dim>
    MasterSurface<dim>::displacement(const unsigned int                   face,
                                     const Point<dim - 1>                &xi,
                                     const TrilinosWrappers::MPI::Vector &u) const
    {
      Tensor<1, dim> result;
      for (unsigned int k = 0; k < n_nodes; ++k)
        {
          const double N = node_element.shape_value(k, xi);
          for (unsigned int d = 0; d < dim; ++d)
            result[d] += N * u(face_dofs[(face * n_nodes + k) * dim + d]);
        }
      return result;
    }

    template <int dim>
    void
    MasterSurface<dim>::shape_values(const Pairing<dim>                   &pairing,
                                     std::vector<types::global_dof_index> &dofs,
                                     std::vector<unsigned int>            &components,
                                     std::vector<double>                  &values) const
    {
      const unsigned int    face = pairing.master_face;
      const Point<dim - 1> &xi   = pairing.master_reference_point;
      dofs.clear();
      components.clear();
      values.clear();
      for (unsigned int k = 0; k < n_nodes; ++k)
        {
          const double N = node_element.shape_value(k, xi);
          for (unsigned int d = 0; d < dim; ++d)
            {
              dofs.push_back(face_dofs[(face * n_nodes + k) * dim + d]);
              components.push_back(d);
              values.push_back(N);
            }
        }
    }

    template <int dim>
    void
    MasterSurface<dim>::shape_gradients(const Pairing<dim>              &pairing,
                                        std::vector<Tensor<1, dim - 1>> &gradients) const
    {
      gradients.clear();
      for (unsigned int k = 0; k < n_nodes; ++k)
        for (unsigned int d = 0; d < dim; ++d)
          gradients.push_back(node_element.shape_grad(k, pairing.master_reference_point));
    }

    template <int dim>
    Tensor<1, dim>
    MasterSurface<dim>::follow(Pairing<dim>                        &pairing,
                               const TrilinosWrappers::MPI::Vector &u,
                               const TrilinosWrappers::MPI::Vector &step_start,
                               const Point<dim> &) const
    {
      if (pairing.master_face < 0)
        return Tensor<1, dim>();
      const unsigned int    face = pairing.master_face;
      const Point<dim - 1> &xi   = pairing.master_reference_point;
      const Tensor<1, dim>  now  = displacement(face, xi, u);
      pairing.master_point       = reference_point(face, xi) + now;

      // the surface's derivatives at ξ for the linearised pairing: the
      // multilinear reference map, then the displacement's nodes
      Tensor<1, dim> dx[dim - 1];
      position(face, xi, dx);
      for (unsigned int a = 0; a < dim - 1; ++a)
        {
          pairing.surface_tangents[a]   = dx[a];
          pairing.increment_gradient[a] = Tensor<1, dim>();
          for (unsigned int b = 0; b < dim - 1; ++b)
            pairing.surface_curvature[a][b] = Tensor<1, dim>();
        }
      if constexpr (dim == 3)
        for (unsigned int v = 0; v < n_vertices; ++v)
          {
            // ∂²/∂ξ_0∂ξ_1 of the bilinear weight: ±1 (the pure second derivatives vanish)
            const double mixed = (((v & 1) ? 1. : -1.) * ((v & 2) ? 1. : -1.));
            pairing.surface_curvature[0][1] += mixed * face_vertices[face * n_vertices + v];
          }
      for (unsigned int k = 0; k < n_nodes; ++k)
        {
          const Tensor<1, dim> &u_k      = node_displacements[face * n_nodes + k];
          const auto            gradient = node_element.shape_grad(k, xi);
          const auto            hessian  = node_element.shape_grad_grad(k, xi);
          Tensor<1, dim>        increment;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const types::global_dof_index dof = face_dofs[(face * n_nodes + k) * dim + d];
              increment[d]                      = u(dof) - step_start(dof);
            }
          for (unsigned int a = 0; a < dim - 1; ++a)
            {
              pairing.increment_gradient[a] += gradient[a] * increment;
              for (unsigned int b = 0; b < dim - 1; ++b)
                pairing.surface_curvature[a][b] += hessian[a][b] * u_k;
            }
        }
      if constexpr (dim == 3)
        pairing.surface_curvature[1][0] = pairing.surface_curvature[0][1];
      return now - displacement(face, xi, step_start);
    }

    template class MasterSurface<2>;
    template class MasterSurface<3>;
  } // namespace Contact
} // namespace StabilizedLagrangian
