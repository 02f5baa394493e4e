#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>

#include <stabilized_lagrangian/contact/segments.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cmath>
#include <limits>
#include <memory>

namespace StabilizedLagrangian
{
  template <int dim>
  void
  ContactProblem<dim>::setup_contact_points()
  {
    contact_faces.clear();
    unsigned int n_points = 0;
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (spaces.is_contact_face(cell, f))
            {
              contact_faces.push_back(ContactFace{cell, f, n_points, nullptr, nullptr, nullptr});
              n_points += contact_quadrature.size();
            }
    set_consistent_nodal_weights();
    set_dual_multiplier_basis();
    contact_states.assign(n_points, ContactPointState<dim>());
    contact_zones.assign(contact_faces, contact_quadrature, contact_states);
    for (auto &state : contact_states)
      if (!law.friction_law_of(state).threshold_depends_on_pressure())
        state.friction_threshold = law.friction_law_of(state).threshold(0.);
    setup_contact_conditions();

    // initial statuses from the initial configuration: touching points are in contact
    sparsity_ready = false;
    update_pairings(true);
    setup_sparsity();
    nested_loops.update_statuses();
    if (!free_rigid_motions.empty() && points_in_contact() == 0)
      close_nearest_points();
  }

  template <int dim>
  void
  ContactProblem<dim>::set_consistent_nodal_weights()
  {
    // With nodal quadrature the multiplier coupling is diagonal, ∫ψ_a f ≈ w_a f(x_a),
    // and the nodal λ_a balances the nodal force F_a = w_a λ_a. A uniform
    // pressure p has the consistent nodal forces p ∫_F ℓ_a dΓ, so λ_a = p only
    // if w_a = ∫_F ℓ_a dΓ. The Gauss–Lobatto weight times the Jacobian at the
    // node is that integral where the Jacobian is constant (a straight edge, a
    // parallelogram face), not elsewhere (a distorted hexahedron's face).
    // (linear triangles have a constant Jacobian: their vertex weights are consistent)
    // Axisymmetric: w_a = ∫_F ℓ_a 2πr dΓ, positive also at a node on the axis,
    // where the Gauss–Lobatto weight 2πr·J vanishes.
    if (contact_parameters.quadrature != Parameters::ContactQuadrature::gauss_lobatto ||
        (dim == 3 && body_mesh.simplex()))
      return;
    const unsigned int n_1d =
        static_cast<unsigned int>(std::lround(std::pow(contact_quadrature.size(), 1. / (dim - 1))));
    const QGaussLobatto<1> nodes_1d(n_1d);
    const auto lagrange = Polynomials::generate_complete_Lagrange_basis(nodes_1d.get_points());
    // ℓ_q(ξ) = Π_d L_{q_d}(ξ_d) at the points of a Gauss rule exact for ℓ_q J on plane faces
    const QGauss<dim - 1> gauss(n_1d + 1);
    FullMatrix<double>    shape(contact_quadrature.size(), gauss.size());
    for (unsigned int q = 0; q < contact_quadrature.size(); ++q)
      for (unsigned int g = 0; g < gauss.size(); ++g)
        {
          shape(q, g) = 1.;
          for (unsigned int d = 0; d < dim - 1; ++d)
            for (unsigned int i = 0; i < n_1d; ++i)
              if (std::abs(nodes_1d.point(i)[0] - contact_quadrature.point(q)[d]) < 1e-12)
                shape(q, g) *= lagrange[i].value(gauss.point(g)[d]);
        }
    FEFaceValues<dim> gauss_values(*fe_u, gauss, update_JxW_values | update_quadrature_points);
    FEFaceValues<dim> nodal_values(
        *fe_u, contact_quadrature, update_JxW_values | update_quadrature_points);
    for (auto &face : contact_faces)
      {
        gauss_values.reinit(face.cell, face.face_no);
        nodal_values.reinit(face.cell, face.face_no);
        std::vector<double> weights(contact_quadrature.size(), 0.);
        double              difference = 0., smallest = std::numeric_limits<double>::max();
        for (unsigned int q = 0; q < weights.size(); ++q)
          {
            for (unsigned int g = 0; g < gauss.size(); ++g)
              weights[q] += shape(q, g) * gauss_values.JxW(g) *
                            spaces.radial_weight(gauss_values.quadrature_point(g));
            difference = std::max(
                difference,
                std::abs(weights[q] - nodal_values.JxW(q) *
                                          spaces.radial_weight(nodal_values.quadrature_point(q))));
            smallest = std::min(smallest, weights[q]);
          }
        // (a face so distorted that a weight is not positive keeps the lumped ones)
        if (difference > 1e-12 * face.cell->face(face.face_no)->measure() *
                             spaces.radial_weight(face.cell->face(face.face_no)->center()) &&
            smallest > 0.)
          face.nodal_weights = std::make_shared<const std::vector<double>>(weights);
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::update_pairings(const bool resegment)
  {
    update_partner_configuration();
    const bool   new_points = resegment && update_segments();
    PointRefresh pairing;
    pairing.pairing = true;
    refresh_contact_points(pairing, [](const auto &, const auto &, const auto &) {});
    if (new_points)
      {
        // the new points take the threshold and status of the current iterate,
        // which the loops would give them
        nested_loops.update_friction_thresholds();
        nested_loops.update_statuses();
      }
    if (sparsity_ready && (sparsity_stale || pairings_left_sparsity()))
      setup_sparsity();
  }

  template <int dim>
  bool
  ContactProblem<dim>::update_segments()
  {
    // the faces' corners (the vertices of a triangle face)
    FaceEvaluator                       ends(spaces, body_mesh.face_nodes(1), false);
    std::vector<ContactFace>            faces;
    std::vector<ContactPointState<dim>> states;
    int                                 changed = 0;
    for (const auto &face : contact_faces)
      {
        ends.reinit(face, ghosted_solution);
        ContactFace cut_face{face.cell,
                             face.face_no,
                             static_cast<unsigned int>(states.size()),
                             nullptr,
                             nullptr,
                             face.dual_basis};
        cut_face.segments                   = face_segments(ends);
        const Quadrature<dim - 1> &old_rule = face.points(contact_quadrature);
        const Quadrature<dim - 1> &new_rule = cut_face.points(contact_quadrature);
        bool                       same     = old_rule.size() == new_rule.size();
        for (unsigned int q = 0; q < new_rule.size() && same; ++q)
          same = old_rule.point(q).distance(new_rule.point(q)) < 1e-12;
        if (same)
          {
            cut_face.segments      = face.segments;
            cut_face.nodal_weights = face.nodal_weights;
            states.insert(states.end(),
                          contact_states.begin() + face.first_point,
                          contact_states.begin() + face.first_point + old_rule.size());
          }
        else
          {
            changed = 1;
            states.resize(states.size() + new_rule.size());
          }
        faces.push_back(cut_face);
      }
    contact_faces  = faces;
    contact_states = states;
    contact_zones.assign(contact_faces, contact_quadrature, contact_states);
    return Utilities::MPI::max(changed, mpi_communicator) == 1;
  }

  template <int dim>
  std::shared_ptr<const Quadrature<dim - 1>>
  ContactProblem<dim>::face_segments(const FaceEvaluator &corners) const
  {
    std::vector<Point<dim>> at_corners;
    for (unsigned int v = 0; v < corners.n_points(); ++v)
      at_corners.push_back(corners.kinematics(v).position);
    BoundingBox<dim> box(at_corners);
    const double     diameter = std::sqrt(box.side_length(0) * box.side_length(0) +
                                      box.side_length(1) * box.side_length(1) +
                                      (dim == 3 ? std::pow(box.side_length(dim - 1), 2) : 0.));
    box.extend(0.5 * diameter);
    const std::vector<Point<dim>> master_vertices = partner->vertices_near(box);
    if (master_vertices.empty())
      return nullptr;
    if constexpr (dim == 3)
      {
        // a quadrilateral or triangle face against the master's faces, with
        // the collapsed rule of the face quadrature's degree on each part
        const unsigned int n_1d =
            std::max(fe_pair->displacement_degree(), fe_pair->multiplier_degree()) + 1;
        return Contact::face_segments(
            at_corners, master_vertices, partner->vertices_per_face(), 2 * n_1d - 1);
      }
    else
      {
        const Point<dim>     A      = at_corners[0];
        const Tensor<1, dim> AB     = at_corners[1] - A;
        const double         length = AB.norm();
        // the parameters in (0, 1) of the master's vertices projected on the face
        std::vector<double> cuts = {0., 1.};
        for (const auto &vertex : master_vertices)
          {
            const double s = (vertex - A) * AB / (length * length);
            if (s > 1e-8 && s < 1. - 1e-8 && (vertex - (A + s * AB)).norm() <= length)
              cuts.push_back(s);
          }
        std::sort(cuts.begin(), cuts.end());
        cuts.erase(std::unique(cuts.begin(),
                               cuts.end(),
                               [](const double a, const double b) { return b - a < 1e-8; }),
                   cuts.end());
        if (cuts.size() <= 2)
          return nullptr;
        std::vector<Point<dim - 1>> points;
        std::vector<double>         weights;
        for (unsigned int k = 0; k + 1 < cuts.size(); ++k)
          for (unsigned int q = 0; q < contact_quadrature.size(); ++q)
            {
              const double width = cuts[k + 1] - cuts[k];
              points.emplace_back(cuts[k] + width * contact_quadrature.point(q)[0]);
              weights.push_back(width * contact_quadrature.weight(q));
            }
        return std::make_shared<const Quadrature<dim - 1>>(points, weights);
      }
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                               \
  template void ContactProblem<dim>::setup_contact_points();                              \
  template void ContactProblem<dim>::set_consistent_nodal_weights();                      \
  template void ContactProblem<dim>::update_pairings(bool);                               \
  template bool ContactProblem<dim>::update_segments();                                   \
  template std::shared_ptr<const Quadrature<dim - 1>> ContactProblem<dim>::face_segments( \
      const FaceEvaluator &) const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
