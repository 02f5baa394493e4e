#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <stabilized_lagrangian/contact/contact_edge.h>
#include <stabilized_lagrangian/solver/error_estimator.h>
#include <stabilized_lagrangian/solver/stress_recovery.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace StabilizedLagrangian
{
  // The pressure estimate of Γc (doc/formulation.md, "Error estimate"): the
  // part of ErrorEstimator that compares λ_n with the normal traction of the
  // recovered stress, or with the square-root onset where the contact zone ends.

  template <int dim>
  typename StressRecovery<dim>::Sampler
  ErrorEstimator<dim>::barlow_sampler(const TrilinosWrappers::MPI::Vector &u) const
  {
    // (on simplices the Gauss points of the same order: the centroid for P1)
    const Quadrature<dim> barlow =
        view.cell_shape.template get_gauss_type_quadrature<dim>(view.displacement_fe.degree);
    const auto fe_values = std::make_shared<FEValues<dim>>(
        view.displacement_fe, barlow, update_values | update_gradients | update_quadrature_points);
    return [this, &u, fe_values](const DoFCell &cell) {
      const unsigned int          n_points = fe_values->n_quadrature_points;
      std::vector<Tensor<2, dim>> gradients(n_points);
      std::vector<Tensor<1, dim>> values(n_points);
      fe_values->reinit(cell);
      (*fe_values)[FEValuesExtractors::Vector(0)].get_function_gradients(u, gradients);
      (*fe_values)[FEValuesExtractors::Vector(0)].get_function_values(u, values);
      std::vector<std::pair<Point<dim>, Tensor<2, dim>>> samples;
      for (unsigned int q = 0; q < n_points; ++q)
        {
          const Point<dim> &x = fe_values->quadrature_point(q);
          samples.emplace_back(
              x, stress_at(cell, gradients[q], x, hoop_strain(x, values[q], gradients[q])));
        }
      return samples;
    };
  }

  template <int dim>
  double
  ErrorEstimator<dim>::pressure_estimate(const TrilinosWrappers::MPI::Vector &u,
                                         Vector<double>                      *per_cell) const
  {
    // ‖p* − λ_n‖ / ‖λ_n‖ on Γc, p* = −N·P*N from the recovered stress P*,
    // with a Gauss rule two orders above the pair's on each face: between
    // the nodes is where a linear λ_n departs most from a curved pressure
    const FiniteElement<dim> &fe   = view.displacement_fe;
    const Quadrature<dim - 1> rule = face_gauss(fe.degree + 2);
    FaceEvaluator<dim>        evaluator(view.spaces, rule, false);
    FEFaceValues<dim>   face_values(fe, rule, update_normal_vectors | update_quadrature_points);
    StressRecovery<dim> recovery(view.displacement_dofs, fe.degree, barlow_sampler(u));
    // the faces that hold the end of the contact zone: the square-root onset
    // fitted to their contact points, integrated finely across its kink
    FaceEvaluator<dim> nodes(view.spaces, view.contact_quadrature);
    // (the finest simplex rule on triangle faces)
    const Quadrature<dim - 1> edge_rule =
        (dim == 3 && view.simplex)
            ? face_gauss(4)
            : Quadrature<dim - 1>(QIterated<dim - 1>(QGauss<1>(2), dim == 2 ? 16 : 8));
    FaceEvaluator<dim> edge_evaluator(view.spaces, edge_rule, false);
    FEFaceValues<dim>  edge_values(fe, edge_rule, update_quadrature_points);
    const double       master_compliance = deformable_master_compliance();
    double             mismatch = 0., norm = 0., area = 0.;
    // the mismatch at the points of a face evaluator against a pressure
    const auto add_mismatch = [&](const FaceEvaluator<dim> &at, const auto &pressure) {
      for (unsigned int q = 0; q < at.n_points(); ++q)
        {
          const ContactKinematics<dim> k = at.kinematics(q);
          mismatch += std::pow(pressure(q) - k.contact_pressure, 2) * k.JxW;
          norm += k.contact_pressure * k.contact_pressure * k.JxW;
          area += k.JxW;
        }
    };
    for (const auto &face : view.contact.faces())
      {
        const double before = mismatch;
        face_values.reinit(face.cell, face.face_no);
        Tensor<1, dim> normal;
        for (unsigned int q = 0; q < rule.size(); ++q)
          normal += face_values.normal_vector(q);
        normal /= normal.norm();
        const Contact::SquareRootOnset<dim> onset =
            square_root_onset(face, nodes, normal, master_compliance);
        if (onset.valid())
          {
            edge_values.reinit(face.cell, face.face_no);
            edge_evaluator.reinit(face, view.ghosted_solution);
            add_mismatch(edge_evaluator, [&](const unsigned int q) {
              return onset.pressure(edge_values.quadrature_point(q));
            });
          }
        else
          {
            evaluator.reinit(face, view.ghosted_solution);
            const auto recovered =
                recovery.at(face.cell, face.face_no, normal, face_values.get_quadrature_points());
            add_mismatch(evaluator, [&](const unsigned int q) {
              const Tensor<1, dim> &N = face_values.normal_vector(q);
              return -(recovered[q] * N) * N;
            });
          }
        if (per_cell != nullptr)
          (*per_cell)[face.cell->active_cell_index()] += mismatch - before;
      }
    mismatch = Utilities::MPI::sum(mismatch, view.communicator);
    norm     = Utilities::MPI::sum(norm, view.communicator);
    area     = Utilities::MPI::sum(area, view.communicator);
    // Without contact λ_n is round-off (a pressure below negligible_pressure
    // everywhere), and a ratio of round-offs is no error estimate: it read
    // 5e145 on a scene that never touched. Nothing is estimated then (0).
    const double negligible = view.negligible_pressure;
    return norm > negligible * negligible * area ? std::sqrt(mismatch / norm) : 0.;
  }

  template <int dim>
  Contact::SquareRootOnset<dim>
  ErrorEstimator<dim>::square_root_onset(const ContactFace<dim> &face,
                                         FaceEvaluator<dim>     &nodes,
                                         const Tensor<1, dim>   &normal,
                                         const double            master_compliance) const
  {
    const unsigned int n_points     = face.points(view.contact_quadrature).size();
    unsigned int       n_in_contact = 0;
    for (unsigned int q = 0; q < n_points; ++q)
      n_in_contact += view.contact.point(face, q).in_contact;
    // a face all in contact or all open holds no end of the contact zone
    if (n_in_contact == 0 || n_in_contact == n_points)
      return Contact::SquareRootOnset<dim>();
    std::vector<Point<dim>> points(n_points);
    std::vector<bool>       in_contact(n_points);
    std::vector<double>     pressures(n_points), gaps(n_points);
    bool                    deformable = false;
    nodes.reinit(face, view.ghosted_solution);
    for (unsigned int q = 0; q < n_points; ++q)
      {
        const ContactPointState<dim> &state = view.contact.point(face, q);
        const ContactKinematics<dim>  k     = nodes.kinematics(q);
        points[q]                           = k.position - k.displacement;
        in_contact[q]                       = state.in_contact;
        pressures[q]                        = k.contact_pressure;
        gaps[q]                             = state.pairing.gap(k.position);
        deformable                          = deformable || state.pairing.master_face >= 0;
      }
    const Materials::Interface<dim> &material = material_of(face.cell);
    const double                     compliance =
        (1. - std::pow(material.poissons_ratio(), 2)) / material.youngs_modulus() +
        (deformable ? master_compliance : 0.);
    return Contact::SquareRootOnset<dim>(
        points, in_contact, pressures, gaps, normal, 1. / compliance);
  }

  template <int dim>
  double
  ErrorEstimator<dim>::deformable_master_compliance() const
  {
    // (1 − ν²)/E of the body that holds the master surface, 0 without one
    double compliance = 0.;
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              view.master_boundaries.count(cell->face(f)->boundary_id()) > 0)
            {
              const Materials::Interface<dim> &material = material_of(cell);
              compliance                                = std::max(compliance,
                                    (1. - std::pow(material.poissons_ratio(), 2)) /
                                        material.youngs_modulus());
            }
    return Utilities::MPI::max(compliance, view.communicator);
  }

  template <int dim>
  Vector<float>
  ErrorEstimator<dim>::pressure_indicators(const TrilinosWrappers::MPI::Vector &u)
  {
    // the recovered stress reads the committed state as estimate() does
    share_ghost_history();
    view.body_response.compute_volume_fields(u);
    Vector<double> squared(view.triangulation.n_active_cells());
    pressure_estimate(u, &squared);
    return Vector<float>(squared.begin(), squared.end());
  }

  // (the rest of ErrorEstimator is instantiated in error_estimator.cc)
  template double
  ErrorEstimator<2>::pressure_estimate(const TrilinosWrappers::MPI::Vector &,
                                       Vector<double> *) const;
  template double
  ErrorEstimator<3>::pressure_estimate(const TrilinosWrappers::MPI::Vector &,
                                       Vector<double> *) const;
  template Vector<float>
  ErrorEstimator<2>::pressure_indicators(const TrilinosWrappers::MPI::Vector &);
  template Vector<float>
  ErrorEstimator<3>::pressure_indicators(const TrilinosWrappers::MPI::Vector &);
} // namespace StabilizedLagrangian
