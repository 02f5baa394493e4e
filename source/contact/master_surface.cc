// The master surface of a second deformable body (doc/formulation.md, "Two
// deformable bodies"): its faces as their owners describe them, the faces a
// rank holds, their deformed geometry and the pairing's DoFs and derivatives.
// The contact search over the held faces (R-tree, gathering, closest-point
// projection) is in master_surface_search.cc.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/geometry_info.h>

#include <deal.II/fe/fe.h>

#include <stabilized_lagrangian/contact/master_surface.h>
#include <stabilized_lagrangian/plugins.h>

#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <limits>
#include <map>
#include <numeric>

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

      /**
       * The node of @p node_element (FE_Q<dim−1>) at the support point of
       * each DoF of a face of @p fe: the face's DoFs in the node-major order
       * of a master face.
       */
      template <int dim>
      std::vector<unsigned int>
      node_of_face_dofs(const FiniteElement<dim> &fe, const FE_Q<dim - 1> &node_element)
      {
        const std::vector<Point<dim - 1>> &face_points = fe.get_unit_face_support_points();
        const std::vector<Point<dim - 1>> &node_points = node_element.get_unit_support_points();
        std::vector<unsigned int>          node_of(fe.n_dofs_per_face());
        for (unsigned int i = 0; i < node_of.size(); ++i)
          {
            node_of[i] = numbers::invalid_unsigned_int;
            for (unsigned int k = 0; k < node_element.n_dofs_per_cell(); ++k)
              if (face_points[i].distance(node_points[k]) < 1e-10)
                node_of[i] = k;
            AssertThrow(node_of[i] != numbers::invalid_unsigned_int, ExcInternalError());
          }
        return node_of;
      }

      /**
       * ±1: the sign that turns the normal of the face's own parametrisation
       * by its @p vertices (at its centre) outward, away from the centre
       * @p cell_center of its cell; @p face_center is the face's centre.
       */
      template <int dim>
      double
      outward_sign(const std::vector<Point<dim>> &vertices,
                   const Point<dim>              &face_center,
                   const Point<dim>              &cell_center)
      {
        Point<dim - 1> centre;
        for (unsigned int a = 0; a < dim - 1; ++a)
          centre[a] = 0.5;
        Tensor<1, dim> dX[dim - 1];
        for (unsigned int v = 0; v < vertices.size(); ++v)
          {
            Tensor<1, dim - 1> gradient;
            vertex_weight<dim>(v, centre, gradient);
            for (unsigned int a = 0; a < dim - 1; ++a)
              dX[a] += gradient[a] * vertices[v];
          }
        Tensor<1, dim> n;
        if constexpr (dim == 2)
          n = Tensor<1, dim>({dX[0][1], -dX[0][0]});
        else
          n = cross_product_3d(dX[0], dX[1]);
        return n * (face_center - cell_center) > 0. ? 1. : -1.;
      }
    } // namespace

    template <int dim>
    MasterSurface<dim>::MasterSurface(const DoFHandler<dim>              &dof_handler,
                                      const std::set<types::boundary_id> &boundary_ids,
                                      const MPI_Comm                      communicator,
                                      const bool                          replicated,
                                      const double                        search_distance)
        : communicator(communicator)
        , replicated(replicated)
        , search_distance(search_distance)
        , node_element(dof_handler.get_fe().degree)
        , n_nodes(node_element.n_dofs_per_cell())
        , surface_dofs(dof_handler.n_dofs())
    {
      AssertThrow(search_distance > 0., ExcInternalError());
      // a face is multilinear in its 2^(dim-1) vertices; every rank has the same
      // element, so every rank refuses together
      if (!dof_handler.get_fe().reference_cell().face_reference_cell(0).is_hyper_cube())
        throw InputError("Contact/Master boundary ids: contact between two deformable bodies "
                         "meshed with tetrahedra needs a master surface of triangle faces, which "
                         "is not built yet (the master surface holds line and quadrilateral "
                         "faces); in 3D mesh the bodies with hexahedra.");
      collect_owned_faces(dof_handler, boundary_ids);
      number_owned_faces();
      if (replicated)
        {
          std::vector<FaceRecord> all;
          for (const auto &part : Utilities::MPI::all_gather(communicator, pack(owned_faces)))
            for (const auto &record : unpack(part))
              all.push_back(record);
          hold(all);
        }
    }

    template <int dim>
    void
    MasterSurface<dim>::collect_owned_faces(const DoFHandler<dim>              &dof_handler,
                                            const std::set<types::boundary_id> &boundary_ids)
    {
      const FiniteElement<dim>            &fe      = dof_handler.get_fe();
      const std::vector<unsigned int>      node_of = node_of_face_dofs(fe, node_element);
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_face());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                boundary_ids.count(cell->face(f)->boundary_id()) > 0)
              {
                const auto face = cell->face(f);
                FaceRecord record;
                face->get_dof_indices(dofs);
                record.dofs.resize(n_nodes * dim);
                for (unsigned int i = 0; i < dofs.size(); ++i)
                  record.dofs[node_of[i] * dim + fe.face_system_to_component_index(i).first] =
                      dofs[i];
                for (unsigned int v = 0; v < n_vertices; ++v)
                  record.vertices.push_back(face->vertex(v));
                record.sign = outward_sign<dim>(record.vertices, face->center(), cell->center());
                owned_faces.push_back(record);
              }
    }

    template <int dim>
    void
    MasterSurface<dim>::number_owned_faces()
    {
      // global ids: the owner's offset plus the place among its faces
      const std::vector<unsigned int> counts =
          Utilities::MPI::all_gather(communicator, static_cast<unsigned int>(owned_faces.size()));
      const unsigned int rank   = Utilities::MPI::this_mpi_process(communicator);
      n_global_faces            = std::accumulate(counts.begin(), counts.end(), 0u);
      const unsigned int offset = std::accumulate(counts.begin(), counts.begin() + rank, 0u);
      for (unsigned int i = 0; i < owned_faces.size(); ++i)
        owned_faces[i].id = offset + i;
    }

    template <int dim>
    BoundingBox<dim>
    MasterSurface<dim>::padded_box(const std::vector<Point<dim>> &points)
    {
      BoundingBox<dim> box(points);
      const auto &[low, high] = box.get_boundary_points();
      box.extend(0.1 * low.distance(high));
      return box;
    }

    template <int dim>
    typename MasterSurface<dim>::PackedFaces
    MasterSurface<dim>::pack(const std::vector<FaceRecord> &records) const
    {
      PackedFaces packed;
      for (const FaceRecord &record : records)
        {
          for (const Point<dim> &vertex : record.vertices)
            for (unsigned int d = 0; d < dim; ++d)
              packed.first.push_back(vertex[d]);
          packed.first.push_back(record.sign);
          const auto &[low, high] = record.box.get_boundary_points();
          for (unsigned int d = 0; d < dim; ++d)
            {
              packed.first.push_back(low[d]);
              packed.first.push_back(high[d]);
            }
          packed.second.push_back(record.id);
          packed.second.insert(packed.second.end(), record.dofs.begin(), record.dofs.end());
        }
      return packed;
    }

    template <int dim>
    std::vector<typename MasterSurface<dim>::FaceRecord>
    MasterSurface<dim>::unpack(const PackedFaces &packed) const
    {
      const unsigned int n_doubles = n_vertices * dim + 1 + 2 * dim;
      const unsigned int n_indices = 1 + n_nodes * dim;
      AssertThrow(packed.first.size() % n_doubles == 0 &&
                      packed.second.size() == packed.first.size() / n_doubles * n_indices,
                  ExcInternalError());
      std::vector<FaceRecord> records(packed.first.size() / n_doubles);
      for (unsigned int r = 0; r < records.size(); ++r)
        {
          const double *geometry = packed.first.data() + r * n_doubles;
          for (unsigned int v = 0; v < n_vertices; ++v)
            {
              Point<dim> vertex;
              for (unsigned int d = 0; d < dim; ++d)
                vertex[d] = geometry[v * dim + d];
              records[r].vertices.push_back(vertex);
            }
          records[r].sign = geometry[n_vertices * dim];
          Point<dim> low, high;
          for (unsigned int d = 0; d < dim; ++d)
            {
              low[d]  = geometry[n_vertices * dim + 1 + 2 * d];
              high[d] = geometry[n_vertices * dim + 2 + 2 * d];
            }
          records[r].box                         = BoundingBox<dim>({low, high});
          const types::global_dof_index *indices = packed.second.data() + r * n_indices;
          records[r].id                          = static_cast<unsigned int>(indices[0]);
          records[r].dofs.assign(indices + 1, indices + n_indices);
        }
      return records;
    }

    template <int dim>
    void
    MasterSurface<dim>::hold(const std::vector<FaceRecord> &records)
    {
      for (const FaceRecord &record : records)
        {
          AssertThrow(slots.count(record.id) == 0, ExcInternalError());
          slots[record.id] = face_ids.size();
          face_ids.push_back(record.id);
          face_vertices.insert(face_vertices.end(), record.vertices.begin(), record.vertices.end());
          face_sign.push_back(record.sign);
          face_dofs.insert(face_dofs.end(), record.dofs.begin(), record.dofs.end());
          for (const auto dof : record.dofs)
            surface_dofs.add_index(dof);
        }
      surface_dofs.compress();
      node_displacements.resize(face_ids.size() * n_nodes);

      // held faces sharing a node
      std::map<types::global_dof_index, std::vector<unsigned int>> faces_at;
      for (unsigned int f = 0; f < face_ids.size(); ++f)
        for (unsigned int k = 0; k < n_nodes; ++k)
          faces_at[face_dofs[(f * n_nodes + k) * dim]].push_back(face_ids[f]);
      face_neighbours.assign(face_ids.size(), {});
      for (unsigned int f = 0; f < face_ids.size(); ++f)
        {
          std::set<unsigned int> near;
          for (unsigned int k = 0; k < n_nodes; ++k)
            for (const unsigned int g : faces_at[face_dofs[(f * n_nodes + k) * dim]])
              near.insert(g);
          face_neighbours[f].assign(near.begin(), near.end());
        }
    }

    template <int dim>
    unsigned int
    MasterSurface<dim>::slot(const unsigned int face) const
    {
      const auto found = slots.find(face);
      AssertThrow(found != slots.end(),
                  ExcMessage("master face " + std::to_string(face) + " is not held here"));
      return found->second;
    }

    template <int dim>
    BoundingBox<dim>
    MasterSurface<dim>::deformed_box(const FaceRecord                    &record,
                                     const TrilinosWrappers::MPI::Vector *u) const
    {
      const std::vector<Point<dim - 1>> &node_points = node_element.get_unit_support_points();
      std::vector<Point<dim>>            points;
      for (unsigned int k = 0; k < n_nodes; ++k)
        {
          Point<dim>         X;
          Tensor<1, dim - 1> gradient;
          for (unsigned int v = 0; v < n_vertices; ++v)
            X += vertex_weight<dim>(v, node_points[k], gradient) * record.vertices[v];
          if (u != nullptr)
            for (unsigned int d = 0; d < dim; ++d)
              X[d] += (*u)(record.dofs[k * dim + d]);
          points.push_back(X);
        }
      return padded_box(points);
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
      dofs.clear();
      components.clear();
      values.clear();
      if (pairing.master_face < 0)
        return;
      const unsigned int    face = slot(pairing.master_face);
      const Point<dim - 1> &xi   = pairing.master_reference_point;
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
      if (pairing.master_face < 0)
        return;
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
      const unsigned int    face = slot(pairing.master_face);
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

    template <int dim>
    ArrayView<const types::global_dof_index>
    MasterSurface<dim>::face_dof_indices(const unsigned int face) const
    {
      return {face_dofs.data() + slot(face) * n_nodes * dim, n_nodes * dim};
    }

    template <int dim>
    const std::vector<unsigned int> &
    MasterSurface<dim>::faces_near(const Pairing<dim> &pairing) const
    {
      if (pairing.master_face < 0)
        return no_faces;
      return face_neighbours[slot(pairing.master_face)];
    }

    template class MasterSurface<2>;
    template class MasterSurface<3>;
  } // namespace Contact
} // namespace StabilizedLagrangian
