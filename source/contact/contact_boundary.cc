#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <stabilized_lagrangian/contact/contact_boundary.h>
#include <stabilized_lagrangian/contact/segments.h>
#include <stabilized_lagrangian/contact/weighted_conditions.h>

#include <cmath>
#include <limits>
#include <memory>

namespace StabilizedLagrangian
{
  template <int dim>
  void
  ContactBoundary<dim>::setup()
  {
    contact_faces.clear();
    unsigned int n_points = 0;
    for (const auto &cell : view.dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (view.spaces.is_contact_face(cell, f))
            {
              contact_faces.push_back(
                  ContactFace<dim>{cell, f, n_points, nullptr, nullptr, nullptr});
              n_points += view.contact_quadrature.size();
            }
    set_consistent_nodal_weights();
    set_dual_multiplier_basis();
    states.assign(n_points, ContactPointState<dim>());
    view.zones.assign(contact_faces, view.contact_quadrature, states);
    for (auto &state : states)
      if (!view.law.friction_law_of(state).threshold_depends_on_pressure())
        state.friction_threshold = view.law.friction_law_of(state).threshold(0.);
    setup_conditions();
  }

  template <int dim>
  void
  ContactBoundary<dim>::set_consistent_nodal_weights()
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
    if (view.parameters.quadrature != Parameters::ContactQuadrature::gauss_lobatto ||
        (dim == 3 && view.body_mesh.simplex()))
      return;
    const unsigned int n_1d = static_cast<unsigned int>(
        std::lround(std::pow(view.contact_quadrature.size(), 1. / (dim - 1))));
    const QGaussLobatto<1> nodes_1d(n_1d);
    const auto lagrange = Polynomials::generate_complete_Lagrange_basis(nodes_1d.get_points());
    // ℓ_q(ξ) = Π_d L_{q_d}(ξ_d) at the points of a Gauss rule exact for ℓ_q J on plane faces
    const QGauss<dim - 1> gauss(n_1d + 1);
    FullMatrix<double>    shape(view.contact_quadrature.size(), gauss.size());
    for (unsigned int q = 0; q < view.contact_quadrature.size(); ++q)
      for (unsigned int g = 0; g < gauss.size(); ++g)
        {
          shape(q, g) = 1.;
          for (unsigned int d = 0; d < dim - 1; ++d)
            for (unsigned int i = 0; i < n_1d; ++i)
              if (std::abs(nodes_1d.point(i)[0] - view.contact_quadrature.point(q)[d]) < 1e-12)
                shape(q, g) *= lagrange[i].value(gauss.point(g)[d]);
        }
    FEFaceValues<dim> gauss_values(
        *view.spaces.fe_u, gauss, update_JxW_values | update_quadrature_points);
    FEFaceValues<dim> nodal_values(
        *view.spaces.fe_u, view.contact_quadrature, update_JxW_values | update_quadrature_points);
    for (auto &face : contact_faces)
      {
        gauss_values.reinit(face.cell, face.face_no);
        nodal_values.reinit(face.cell, face.face_no);
        std::vector<double> weights(view.contact_quadrature.size(), 0.);
        double              difference = 0., smallest = std::numeric_limits<double>::max();
        for (unsigned int q = 0; q < weights.size(); ++q)
          {
            for (unsigned int g = 0; g < gauss.size(); ++g)
              weights[q] += shape(q, g) * gauss_values.JxW(g) *
                            view.spaces.radial_weight(gauss_values.quadrature_point(g));
            difference = std::max(
                difference,
                std::abs(weights[q] - nodal_values.JxW(q) * view.spaces.radial_weight(
                                                                nodal_values.quadrature_point(q))));
            smallest = std::min(smallest, weights[q]);
          }
        // (a face so distorted that a weight is not positive keeps the lumped ones)
        if (difference > 1e-12 * face.cell->face(face.face_no)->measure() *
                             view.spaces.radial_weight(face.cell->face(face.face_no)->center()) &&
            smallest > 0.)
          face.nodal_weights = std::make_shared<const std::vector<double>>(weights);
      }
  }

  template <int dim>
  bool
  ContactBoundary<dim>::update_segments()
  {
    // the faces' corners (the vertices of a triangle face)
    FaceEvaluator<dim>                  ends(view.spaces, view.body_mesh.face_nodes(1), false);
    std::vector<ContactFace<dim>>       faces;
    std::vector<ContactPointState<dim>> cut_states;
    int                                 changed = 0;
    for (const auto &face : contact_faces)
      {
        ends.reinit(face, view.ghosted_solution);
        ContactFace<dim> cut_face{face.cell,
                                  face.face_no,
                                  static_cast<unsigned int>(cut_states.size()),
                                  nullptr,
                                  nullptr,
                                  face.dual_basis};
        cut_face.segments                   = face_segments(ends);
        const Quadrature<dim - 1> &old_rule = face.points(view.contact_quadrature);
        const Quadrature<dim - 1> &new_rule = cut_face.points(view.contact_quadrature);
        bool                       same     = old_rule.size() == new_rule.size();
        for (unsigned int q = 0; q < new_rule.size() && same; ++q)
          same = old_rule.point(q).distance(new_rule.point(q)) < 1e-12;
        if (same)
          {
            cut_face.segments      = face.segments;
            cut_face.nodal_weights = face.nodal_weights;
            cut_states.insert(cut_states.end(),
                              states.begin() + face.first_point,
                              states.begin() + face.first_point + old_rule.size());
          }
        else
          {
            changed = 1;
            cut_states.resize(cut_states.size() + new_rule.size());
          }
        faces.push_back(cut_face);
      }
    contact_faces = faces;
    states        = cut_states;
    view.zones.assign(contact_faces, view.contact_quadrature, states);
    return Utilities::MPI::max(changed, view.communicator) == 1;
  }

  template <int dim>
  std::shared_ptr<const Quadrature<dim - 1>>
  ContactBoundary<dim>::face_segments(const FaceEvaluator<dim> &corners) const
  {
    std::vector<Point<dim>> at_corners;
    for (unsigned int v = 0; v < corners.n_points(); ++v)
      at_corners.push_back(corners.kinematics(v).position);
    BoundingBox<dim> box(at_corners);
    const double     diameter = std::sqrt(box.side_length(0) * box.side_length(0) +
                                      box.side_length(1) * box.side_length(1) +
                                      (dim == 3 ? std::pow(box.side_length(dim - 1), 2) : 0.));
    box.extend(0.5 * diameter);
    const std::vector<Point<dim>> master_vertices = view.partner->vertices_near(box);
    if (master_vertices.empty())
      return nullptr;
    if constexpr (dim == 3)
      {
        // a quadrilateral or triangle face against the master's faces, with
        // the collapsed rule of the face quadrature's degree on each part
        const unsigned int n_1d =
            std::max(view.fe_pair->displacement_degree(), view.fe_pair->multiplier_degree()) + 1;
        return Contact::face_segments(
            at_corners, master_vertices, view.partner->vertices_per_face(), 2 * n_1d - 1);
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
          for (unsigned int q = 0; q < view.contact_quadrature.size(); ++q)
            {
              const double width = cuts[k + 1] - cuts[k];
              points.emplace_back(cuts[k] + width * view.contact_quadrature.point(q)[0]);
              weights.push_back(width * view.contact_quadrature.weight(q));
            }
        return std::make_shared<const Quadrature<dim - 1>>(points, weights);
      }
  }

  // `Contact/Complementarity = weighted` (doc/formulation.md, "Weighted
  // complementarity"): the contact and friction conditions hold once per
  // multiplier node j, on the weighted gap g_j = ∫ψ_j g_n / D_j and slip
  // Δs_j = ∫ψ_j Δs / D_j, D_j = ∫ψ_j, as in mortar methods; the displacement
  // sees the multiplier field itself.

  template <int dim>
  void
  ContactBoundary<dim>::set_dual_multiplier_basis()
  {
    // A = D M⁻¹ on each face, M_pr = ∫_F φ_p φ_r, D_pp = ∫_F φ_p = Σ_r M_pr,
    // on the reference face (the multiplier lives there): then
    // ∫_F ψ_p φ_r = D_pp δ_pr (Wohlmuth 2000; Popp, Gitterle, Gee, Wall 2010).
    // M with the contact quadrature (Gauss, degree + 1 points: exact for
    // φ_p φ_r J on plane faces), so that the assembled ∫ψ_j φ_k is diagonal
    // also on curved faces; on segmented faces the segments' rule is exact
    // where the face is plane.
    if (!view.fe_pair->dual_multiplier())
      return;
    // (axisymmetric: M and D with the weight 2πr of the model's measure)
    FEFaceValues<dim> values(*view.spaces.fe_m,
                             view.contact_quadrature,
                             update_values | update_JxW_values | update_quadrature_points);
    for (auto &face : contact_faces)
      {
        values.reinit(view.spaces.multiplier_cell(face.cell), face.face_no);
        // the face's nodes: λ_n's shape functions, ascending base index
        const std::vector<unsigned int> &local = view.spaces.multiplier_face_dofs(face.face_no);
        std::vector<unsigned int>        node_shapes;
        for (const auto &[base, node] :
             multiplier_nodes(*view.spaces.fe_m,
                              local,
                              std::vector<types::global_dof_index>(local.begin(), local.end())))
          node_shapes.push_back(static_cast<unsigned int>(node[0]));
        const unsigned int n = node_shapes.size();
        FullMatrix<double> mass(n, n);
        for (unsigned int q = 0; q < view.contact_quadrature.size(); ++q)
          for (unsigned int p = 0; p < n; ++p)
            for (unsigned int r = 0; r < n; ++r)
              mass(p, r) += values.shape_value(node_shapes[p], q) *
                            values.shape_value(node_shapes[r], q) * values.JxW(q) *
                            view.spaces.radial_weight(values.quadrature_point(q));
        Vector<double> row_sums(n);
        for (unsigned int p = 0; p < n; ++p)
          for (unsigned int r = 0; r < n; ++r)
            row_sums(p) += mass(p, r);
        auto dual = std::make_shared<FullMatrix<double>>(n, n);
        dual->invert(mass);
        for (unsigned int p = 0; p < n; ++p)
          for (unsigned int r = 0; r < n; ++r)
            (*dual)(p, r) *= row_sums(p);
        face.dual_basis = dual;
      }
  }

  template <int dim>
  void
  ContactBoundary<dim>::choose_complementarity()
  {
    if (view.parameters.complementarity_automatic)
      {
        const bool two_bodies =
            !view.parameters.master_ids.empty() || !view.parameters.master_names.empty();
        // Local refinement of a 3D contact surface puts hanging nodes on it in a
        // later cycle; the conditions are chosen once for all cycles.
        const bool local_refinement_3d = dim == 3 && view.adaptive_refinement.cycles > 0 &&
                                         view.adaptive_refinement.criterion !=
                                             Parameters::AdaptiveRefinement::Criterion::uniform;
        using Conditions = Parameters::Complementarity;
        std::pair<Conditions, std::string> choice{Conditions::weighted, "two deformable bodies"};
        if (view.fe_pair->dual_multiplier())
          choice = {Conditions::weighted, "a dual pair: its conditions hold node by node"};
        else if (!two_bodies)
          choice = {Conditions::pointwise, "a rigid obstacle: the seed's formulation"};
        else if (!view.zones.empty())
          choice = {Conditions::pointwise, "contact zones, built for the pointwise conditions"};
        else if (local_refinement_3d)
          choice = {Conditions::pointwise,
                    "adaptive refinement of a 3D contact surface makes hanging nodes"};
        view.chosen.complementarity = choice.first;
        complementarity_choice =
            "Complementarity = automatic: " +
            std::string(view.chosen.weighted_complementarity() ? "weighted" : "pointwise") + " (" +
            choice.second + ")";
      }
    if (!view.zones.empty() && view.chosen.weighted_complementarity())
      throw InputError("Contact/Zone " + view.zones.begin()->name +
                       ": contact zones with their own friction law are built for the "
                       "pointwise conditions only; use Contact/Complementarity = pointwise.");
  }

  template <int dim>
  void
  ContactBoundary<dim>::setup_conditions()
  {
    // A constrained multiplier (a hanging node on Γc, a multiplier on a coarser
    // mesh) is no node of its own: its conditions would have to be split
    // among its masters, which the nodal conditions do not do.
    int constrained = 0;
    if (view.chosen.weighted_complementarity())
      for (const auto index : view.locally_relevant)
        if (index >= view.n_u && view.hanging_constraints.is_constrained(index))
          constrained = 1;
    constrained = Utilities::MPI::max(constrained, view.communicator);
    if (constrained == 1 && view.parameters.complementarity_automatic &&
        !view.fe_pair->dual_multiplier())
      {
        view.chosen.complementarity = Parameters::Complementarity::pointwise;
        complementarity_choice = "Complementarity = automatic: pointwise (constrained multiplier "
                                 "nodes on the contact surface: hanging nodes or a coarser "
                                 "multiplier mesh)";
        constrained            = 0;
      }
    if (!complementarity_choice.empty())
      {
        view.pcout << complementarity_choice << "\n";
        complementarity_choice.clear();
      }
    if (view.chosen.weighted_complementarity() && constrained == 1)
      throw InputError(
          "Contact/Complementarity = weighted needs every multiplier node of the contact "
          "surface free, but this mesh and pair constrain some (hanging nodes on the contact "
          "surface from local refinement, or a pair with the multiplier on a coarser mesh). "
          "Refine the contact surface uniformly, choose another pair, or use "
          "Complementarity = pointwise.");
    if (view.chosen.weighted_complementarity() && dim == 3 && view.body_mesh.simplex() &&
        view.fe_pair->multiplier_degree() > 1)
      throw InputError("Contact/Complementarity = weighted needs a multiplier whose basis "
                       "functions have a positive integral, but the quadratic multiplier on "
                       "the triangle faces of tetrahedra has zero integrals at the vertices. "
                       "Use a P1 multiplier (Finite element pair = P2/P1 or P1/P1) or "
                       "Complementarity = pointwise.");
    condition_set =
        make_contact_conditions(view.chosen.weighted_complementarity(), conditions_data());
    condition_set->setup();
  }

  template <int dim>
  ContactConditionsData<dim>
  ContactBoundary<dim>::conditions_data()
  {
    return ContactConditionsData<dim>{
        view.spaces,
        view.contact_quadrature,
        contact_faces,
        states,
        view.ghosted_solution,
        view.locally_owned,
        view.locally_relevant,
        view.communicator,
        view.law,
        view.zones.default_law(),
        view.chosen.r_n,
        view.chosen.r_t,
        view.loops,
        view.negligible_pressure,
        [this]() { return static_cast<unsigned int>(view.zones.size()); },
        [this](const auto &f) { view.spaces.for_each_contact_multiplier_face(f); }};
  }

#define SL_INSTANTIATE(dim) template class ContactBoundary<dim>;
  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
