#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/contact/contact_boundary.h>

#include <algorithm>
#include <cmath>
#include <cstring>

// Γc's reading: its points' count in contact, its samples for the output and
// the slip, the multiplier mass matrix, and its entries of the run's state
// (RunState), checked as untrusted input when read from a checkpoint.

namespace StabilizedLagrangian
{
  namespace
  {
    /** Whether the entries of the point or tensor @p t are finite (and not beyond 1e150). */
    template <typename T>
    bool
    finite_tensor(const T &t)
    {
      return std::isfinite(t.norm_square());
    }

    /** The flags, indices and geometry of the contact points' states. */
    template <int dim>
    bool
    valid_states(const std::vector<ContactPointState<dim>> &states)
    {
      return std::all_of(states.begin(), states.end(), [](const ContactPointState<dim> &state) {
        // (a bool is one byte, 0 or 1; any other is undefined behaviour once read as bool)
        unsigned char in_contact = 0;
        std::memcpy(&in_contact, &state.in_contact, 1);
        const auto &pairing = state.pairing;
        return in_contact <= 1 && pairing.master_face >= -1 &&
               std::isfinite(state.friction_threshold) && finite_tensor(pairing.master_point) &&
               finite_tensor(pairing.normal) && finite_tensor(pairing.master_reference_point);
      });
    }
  } // namespace

  template <int dim>
  unsigned int
  ContactBoundary<dim>::points_in_contact() const
  {
    unsigned int count = 0;
    for (const auto &state : states)
      count += state.in_contact;
    return Utilities::MPI::sum(count, view.communicator);
  }

  template <int dim>
  std::vector<ContactSample<dim>>
  ContactBoundary<dim>::sample(const Quadrature<dim - 1> &nodes) const
  {
    FaceEvaluator<dim> evaluator(view.spaces, nodes, false);
    evaluator.use_nodal_coefficients();
    condition_set->prepare_sampling();
    std::vector<ContactSample<dim>> samples;
    for (const auto &face : contact_faces)
      {
        evaluator.reinit(face, view.ghosted_solution);
        condition_set->reinit_face(evaluator);
        for (unsigned int q = 0; q < nodes.size(); ++q)
          {
            ContactKinematics<dim> k = evaluator.kinematics(q);
            // with weighted complementarity, the tractions and status of the
            // point's nearest node
            const Contact::PointResponse<dim - 1> *node = condition_set->response_at(evaluator, q);
            // the state of the converged iterate, evaluated afresh at the point
            ContactPointState<dim> state;
            view.law.evaluate_point_state(state, k, PointRefresh{true, true, true});
            const double gap = state.pairing.gap(k.position);
            samples.push_back({face.cell,
                               face.face_no,
                               evaluator.u_values->quadrature_point(q),
                               state,
                               k,
                               node ? *node : view.law.point_response(state, k),
                               gap,
                               Tensor<1, dim>(),
                               0.});
          }
      }
    return samples;
  }

  template <int dim>
  std::map<std::pair<types::global_dof_index, types::global_dof_index>, double>
  ContactBoundary<dim>::multiplier_mass() const
  {
    std::map<std::pair<types::global_dof_index, types::global_dof_index>, double> mass;
    FaceEvaluator<dim> run_basis(view.spaces, view.contact_quadrature),
        nodal_basis(view.spaces, view.contact_quadrature);
    nodal_basis.use_nodal_coefficients();
    for (const auto &face : contact_faces)
      {
        run_basis.reinit(face, view.ghosted_solution);
        nodal_basis.reinit(face, view.ghosted_solution);
        for (unsigned int q = 0; q < run_basis.n_points(); ++q)
          for (unsigned int a = 0; a < run_basis.m_dofs.size(); ++a)
            for (unsigned int b = 0; b < run_basis.m_dofs.size(); ++b)
              if (view.spaces.fe_m->system_to_component_index(run_basis.m_local[a]).first == 0 &&
                  view.spaces.fe_m->system_to_component_index(run_basis.m_local[b]).first == 0)
                mass[{run_basis.m_dofs[a], run_basis.m_dofs[b]}] +=
                    run_basis.psi(a, q) * nodal_basis.psi(b, q) * run_basis.kinematics(q).JxW;
      }
    return mass;
  }

  template <int dim>
  void
  ContactBoundary<dim>::register_state(RunState &state_list)
  {
    using Scope = RunState::Scope;
    // the segments set the contact points' layout: read before the points
    state_list.add(
        "contact faces",
        Scope::step_cut_and_checkpoint,
        [this](StateWriter &out) { out.put(segments_list()); },
        [this](StateReader &in) -> std::function<void()> {
          const std::vector<double> segments = in.get_finite("segment values");
          try
            {
              restore_segments(segments);
            }
          catch (const InputError &e)
            {
              in.damaged(e.what());
            }
          return {};
        },
        RunState::copy_of(contact_faces));
    state_list.add(
        "contact points",
        Scope::step_cut_and_checkpoint,
        [this](StateWriter &out) { out.put(states); },
        [this](StateReader &in) -> std::function<void()> {
          std::vector<ContactPointState<dim>> read;
          in.get(read, "contact points");
          check_points(in, read);
          return [this, read]() { states = read; };
        },
        RunState::copy_of(states));
    state_list.add(
        "contact conditions",
        Scope::step_cut_and_checkpoint,
        [this](StateWriter &out) { out.put(condition_set->owned_states()); },
        [this](StateReader &in) -> std::function<void()> {
          auto values = in.get_finite("nodal state values", condition_set->n_state_values());
          return [this, values]() { condition_set->restore_states(values); };
        },
        [this]() -> std::function<void()> {
          std::shared_ptr<const ContactConditions<dim>> copy = condition_set->copy();
          return [this, copy]() { condition_set->restore(*copy); };
        });
  }

  template <int dim>
  void
  ContactBoundary<dim>::check_points(StateReader                               &in,
                                     const std::vector<ContactPointState<dim>> &read) const
  {
    if (read.size() != states.size())
      in.damaged("it has " + std::to_string(read.size()) + " contact points, the rebuilt mesh " +
                 std::to_string(states.size()));
    if (!valid_states(read))
      in.damaged("its contact points' states hold invalid values");
    const bool rigid_partner = view.chosen.master_boundaries.empty();
    for (const auto &point : read)
      if (point.zone > view.zones.size() || (rigid_partner && point.pairing.master_face >= 0))
        in.damaged("a contact point names a contact zone or master face the scene does not have");
  }

  template <int dim>
  std::vector<double>
  ContactBoundary<dim>::segments_list() const
  {
    // per face: the number of points, their coordinates, their weights
    std::vector<double> segments;
    for (const auto &face : contact_faces)
      {
        const unsigned int n = face.segments ? face.segments->size() : 0;
        segments.push_back(n);
        for (unsigned int q = 0; q < n; ++q)
          for (unsigned int d = 0; d < dim - 1; ++d)
            segments.push_back(face.segments->point(q)[d]);
        for (unsigned int q = 0; q < n; ++q)
          segments.push_back(face.segments->weight(q));
      }
    return segments;
  }

  template <int dim>
  void
  ContactBoundary<dim>::restore_segments(const std::vector<double> &segments)
  {
    // the faces of the checkpoint's mesh, in the same order: each one's rule,
    // a whole number of points whose coordinates and weights the list holds
    std::size_t  k     = 0;
    unsigned int first = 0;
    for (unsigned int f = 0; f < contact_faces.size(); ++f)
      {
        auto        &face     = contact_faces[f];
        const double n_points = k < segments.size() ? segments[k++] : -1.;
        if (!(n_points >= 0. && n_points == std::floor(n_points) &&
              n_points <= static_cast<double>((segments.size() - k) / dim)))
          throw InputError("the segments of contact face " + std::to_string(f) +
                           " do not fit the rebuilt mesh");
        const auto n = static_cast<unsigned int>(n_points);
        if (n > 0)
          {
            std::vector<Point<dim - 1>> points(n);
            std::vector<double>         weights(n);
            for (unsigned int q = 0; q < n; ++q)
              for (unsigned int d = 0; d < dim - 1; ++d)
                points[q][d] = segments[k++];
            for (unsigned int q = 0; q < n; ++q)
              weights[q] = segments[k++];
            face.segments      = std::make_shared<const Quadrature<dim - 1>>(points, weights);
            face.nodal_weights = nullptr;
          }
        else
          face.segments = nullptr;
        face.first_point = first;
        first += (face.segments ? *face.segments : view.contact_quadrature).size();
      }
    if (k != segments.size())
      throw InputError("it holds segments for more contact faces than the rebuilt mesh has");
    states.resize(first);
  }

#define SL_INSTANTIATE(dim)                                                                 \
  template unsigned int                    ContactBoundary<dim>::points_in_contact() const; \
  template std::vector<ContactSample<dim>> ContactBoundary<dim>::sample(                    \
      const Quadrature<dim - 1> &) const;                                                   \
  template std::map<std::pair<types::global_dof_index, types::global_dof_index>, double>    \
                ContactBoundary<dim>::multiplier_mass() const;                              \
  template void ContactBoundary<dim>::register_state(RunState &);                           \
  template void ContactBoundary<dim>::check_points(                                         \
      StateReader &, const std::vector<ContactPointState<dim>> &) const;                    \
  template std::vector<double> ContactBoundary<dim>::segments_list() const;                 \
  template void                ContactBoundary<dim>::restore_segments(const std::vector<double> &);

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
