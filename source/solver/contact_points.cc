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
  ContactProblem<dim>::assign_zones()
  {
    for (const auto &face : contact_faces)
      {
        const auto found = zone_of_boundary.find(face.cell->face(face.face_no)->boundary_id());
        const unsigned int zone = found == zone_of_boundary.end() ? 0 : found->second;
        for (unsigned int q = 0; q < face_quadrature(face).size(); ++q)
          contact_states[face.first_point + q].zone = zone;
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::setup_contact_points()
  {
    contact_faces.clear();
    unsigned int n_points = 0;
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            {
              contact_faces.push_back(ContactFace{cell, f, n_points, nullptr, nullptr, nullptr});
              n_points += contact_quadrature.size();
            }
    set_consistent_nodal_weights();
    set_dual_multiplier_basis();
    contact_states.assign(n_points, ContactPointState<dim>());
    assign_zones();
    for (auto &state : contact_states)
      if (!friction_law_of(state).threshold_depends_on_pressure())
        state.friction_threshold = friction_law_of(state).threshold(0.);
    setup_nodal_conditions();

    // initial statuses from the initial configuration: touching points are in contact
    sparsity_ready = false;
    update_pairings(true);
    setup_sparsity();
    update_statuses();
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
        (dim == 3 && simplex_mesh()))
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
                            radial_weight(gauss_values.quadrature_point(g));
            difference = std::max(
                difference,
                std::abs(weights[q] -
                         nodal_values.JxW(q) * radial_weight(nodal_values.quadrature_point(q))));
            smallest = std::min(smallest, weights[q]);
          }
        // (a face so distorted that a weight is not positive keeps the lumped ones)
        if (difference > 1e-12 * face.cell->face(face.face_no)->measure() *
                             radial_weight(face.cell->face(face.face_no)->center()) &&
            smallest > 0.)
          face.nodal_weights = std::make_shared<const std::vector<double>>(weights);
      }
  }

  template <int dim>
  bool
  ContactProblem<dim>::finite_strain() const
  {
    return std::any_of(materials.begin(), materials.end(), [](const auto &body) {
      return body.model->is_finite_strain();
    });
  }

  // ---------------------------------------------------------------------------
  // Evaluation on contact faces

  template <int dim>
  ContactProblem<dim>::FaceEvaluator::FaceEvaluator(const ContactProblem      &problem,
                                                    const Quadrature<dim - 1> &quadrature,
                                                    const bool                 follow_segments)
      : u_dofs(problem.fe_u->n_dofs_per_cell())
      , problem(problem)
      , quadrature(quadrature)
      , follow_segments(follow_segments)
  {
  }

  template <int dim>
  void
  ContactProblem<dim>::FaceEvaluator::reinit(const ContactFace                   &face,
                                             const TrilinosWrappers::MPI::Vector &ghosted)
  {
    const Quadrature<dim - 1> *wanted =
        (follow_segments && face.segments) ? face.segments.get() : nullptr;
    if (!u_values || wanted != current || wanted != nullptr)
      {
        const Quadrature<dim - 1> &rule = wanted ? *wanted : quadrature;
        u_values                        = std::make_unique<FEFaceValues<dim>>(
            *problem.fe_u, rule, update_values | update_quadrature_points | update_JxW_values);
        m_values = std::make_unique<FEFaceValues<dim>>(*problem.fe_m, rule, update_values);
        current  = wanted;
        u_now.resize(rule.size());
        u_start.resize(rule.size());
      }
    u_values->reinit(face.cell, face.face_no);
    weights           = follow_segments ? face.nodal_weights.get() : nullptr;
    const auto m_cell = problem.multiplier_cell(face.cell);
    m_values->reinit(m_cell, face.face_no);
    face.cell->get_dof_indices(u_dofs);

    std::vector<types::global_dof_index> all_m(problem.fe_m->n_dofs_per_cell());
    m_cell->get_dof_indices(all_m);
    m_dofs.clear();
    m_local.clear();
    m_coefficients.clear();
    for (const unsigned int i : problem.multiplier_face_dofs(face.face_no))
      {
        Assert(all_m[i] < problem.n_multipliers, ExcInternalError());
        m_local.push_back(i);
        m_dofs.push_back(problem.n_u + all_m[i]);
        m_coefficients.push_back(ghosted(problem.n_u + all_m[i]));
      }
    // ψ_a at the points: φ_a, or with a dual basis Σ_r A_pr φ_(r, c) (p the
    // node of a, c its component; the nodes in ascending base index)
    const unsigned int n_m = m_local.size();
    m_shapes.reinit(n_m, u_now.size());
    const FullMatrix<double> *dual = nodal_coefficients ? nullptr : face.dual_basis.get();
    std::vector<unsigned int> node_of(n_m);
    std::vector<std::vector<unsigned int>> of_node;
    if (dual)
      {
        std::map<unsigned int, unsigned int> position;
        for (const unsigned int i : m_local)
          position.emplace(problem.fe_m->system_to_component_index(i).second, 0);
        unsigned int p = 0;
        for (auto &entry : position)
          entry.second = p++;
        of_node.assign(position.size(), std::vector<unsigned int>(problem.fe_m->n_components()));
        for (unsigned int a = 0; a < n_m; ++a)
          {
            const auto [component, base]   = problem.fe_m->system_to_component_index(m_local[a]);
            node_of[a]                     = position[base];
            of_node[node_of[a]][component] = a;
          }
      }
    for (unsigned int a = 0; a < n_m; ++a)
      for (unsigned int q = 0; q < u_now.size(); ++q)
        if (!dual)
          m_shapes(a, q) = m_values->shape_value(m_local[a], q);
        else
          {
            const unsigned int c     = problem.fe_m->system_to_component_index(m_local[a]).first;
            double             value = 0.;
            for (unsigned int r = 0; r < of_node.size(); ++r)
              value += (*dual)(node_of[a], r) * m_values->shape_value(m_local[of_node[r][c]], q);
            m_shapes(a, q) = value;
          }

    const FiniteElement<dim> &fe = *problem.fe_u;
    for (unsigned int q = 0; q < u_now.size(); ++q)
      {
        u_now[q]   = 0.;
        u_start[q] = 0.;
        for (unsigned int i = 0; i < u_dofs.size(); ++i)
          {
            const unsigned int c   = fe.system_to_component_index(i).first;
            const double       phi = u_values->shape_value(i, q);
            u_now[q][c] += ghosted(u_dofs[i]) * phi;
            u_start[q][c] += problem.step_start(u_dofs[i]) * phi;
          }
      }
  }

  template <int dim>
  ContactKinematics<dim>
  ContactProblem<dim>::FaceEvaluator::kinematics(const unsigned int q) const
  {
    ContactKinematics<dim> k;
    k.displacement   = u_now[q];
    k.step_increment = u_now[q] - u_start[q];
    k.position       = u_values->quadrature_point(q) + u_now[q];
    k.JxW            = weights ? (*weights)[q]
                               : u_values->JxW(q) * problem.radial_weight(u_values->quadrature_point(q));
    for (unsigned int a = 0; a < m_local.size(); ++a)
      {
        const unsigned int c = problem.fe_m->system_to_component_index(m_local[a]).first;
        if (c == 0)
          k.contact_pressure += m_coefficients[a] * m_shapes(a, q);
        else
          k.semi_multiplier[c - 1] += m_coefficients[a] * m_shapes(a, q);
      }
    return k;
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
        update_friction_thresholds();
        update_statuses();
      }
    if (sparsity_ready && (sparsity_stale || pairings_left_sparsity()))
      setup_sparsity();
  }

  template <int dim>
  bool
  ContactProblem<dim>::update_segments()
  {
    // the faces' corners (the vertices of a triangle face)
    FaceEvaluator                       ends(*this, face_nodes(1), false);
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
        const Quadrature<dim - 1> &old_rule = face_quadrature(face);
        const Quadrature<dim - 1> &new_rule = face_quadrature(cut_face);
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
    assign_zones();
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

  template <int dim>
  Contact::PointResponse<dim - 1>
  ContactProblem<dim>::point_response(const ContactPointState<dim> &state,
                                      const ContactKinematics<dim> &k) const
  {
    return Contact::PointResponse<dim - 1>(
        k.contact_pressure,
        state.pairing.gap(k.position),
        k.semi_multiplier,
        state.pairing.tangential_components(k.step_increment),
        state.in_contact,
        state.friction_threshold,
        friction_law_of(state).has_friction(),
        chosen.r_n,
        chosen.r_t,
        loops.linearised(Loop::friction)
            ? friction_law_of(state).threshold_derivative(threshold_pressure(k.contact_pressure))
            : 0.);
  }

  template <int dim>
  void
  ContactProblem<dim>::evaluate_point_state(ContactPointState<dim> &state,
                                            ContactKinematics<dim> &k,
                                            const PointRefresh     &what) const
  {
    if (what.pairing)
      state.pairing = partner->project(k.position);
    k.step_increment -=
        partner->follow(state.pairing, ghosted_solution, step_start, k.position - k.step_increment);
    if (what.threshold)
      state.friction_threshold =
          friction_law_of(state).threshold(threshold_pressure(k.contact_pressure));
    if (what.status)
      state.in_contact = status(state, k);
  }

  template <int dim>
  bool
  ContactProblem<dim>::status(const ContactPointState<dim> &state,
                              const ContactKinematics<dim> &k) const
  {
    // A gap within round-off of zero touches: a body resting on the obstacle
    // by a vertex placed 1e-14 mm above it must start in contact, as one at
    // exactly zero does, or a load-controlled body has no support at all.
    const double gap = state.pairing.gap(k.position);
    return Contact::is_in_contact(
        Contact::augmented_pressure(k.contact_pressure, status_gap(gap), chosen.r_n));
  }

  template <int dim>
  double
  ContactProblem<dim>::threshold_pressure(const double contact_pressure) const
  {
    return contact_pressure > negligible_pressure ? contact_pressure
                                                  : contact_start.provisional_pressure;
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                       \
  template void ContactProblem<dim>::assign_zones();                                              \
  template void ContactProblem<dim>::setup_contact_points();                                      \
  template bool ContactProblem<dim>::finite_strain() const;                                       \
  template void ContactProblem<dim>::set_consistent_nodal_weights();                              \
  template class ContactProblem<dim>::FaceEvaluator;                                              \
  template void                                       ContactProblem<dim>::update_pairings(bool); \
  template bool                                       ContactProblem<dim>::update_segments();     \
  template std::shared_ptr<const Quadrature<dim - 1>> ContactProblem<dim>::face_segments(         \
      const FaceEvaluator &) const;                                                               \
  template Contact::PointResponse<dim - 1> ContactProblem<dim>::point_response(                   \
      const ContactPointState<dim> &, const ContactKinematics<dim> &) const;                      \
  template void ContactProblem<dim>::evaluate_point_state(                                        \
      ContactPointState<dim> &, ContactKinematics<dim> &, const PointRefresh &) const;            \
  template bool   ContactProblem<dim>::status(const ContactPointState<dim> &,                     \
                                            const ContactKinematics<dim> &) const;              \
  template double ContactProblem<dim>::threshold_pressure(double) const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
