#include <stabilized_lagrangian/contact/contact_surface.h>

#include <map>

namespace StabilizedLagrangian
{
  // ---------------------------------------------------------------------------
  // Evaluation on contact faces

  template <int dim>
  FaceEvaluator<dim>::FaceEvaluator(const ContactSpaces<dim>  &spaces,
                                    const Quadrature<dim - 1> &quadrature,
                                    const bool                 follow_segments)
      : u_dofs(spaces.fe_u->n_dofs_per_cell())
      , spaces(spaces)
      , quadrature(quadrature)
      , follow_segments(follow_segments)
  {
  }

  template <int dim>
  void
  FaceEvaluator<dim>::reinit(const ContactFace<dim>              &face,
                             const TrilinosWrappers::MPI::Vector &ghosted)
  {
    const Quadrature<dim - 1> *wanted =
        (follow_segments && face.segments) ? face.segments.get() : nullptr;
    if (!u_values || wanted != current || wanted != nullptr)
      {
        const Quadrature<dim - 1> &rule = wanted ? *wanted : quadrature;
        u_values                        = std::make_unique<FEFaceValues<dim>>(
            *spaces.fe_u, rule, update_values | update_quadrature_points | update_JxW_values);
        m_values = std::make_unique<FEFaceValues<dim>>(*spaces.fe_m, rule, update_values);
        current  = wanted;
        u_now.resize(rule.size());
        u_start.resize(rule.size());
      }
    u_values->reinit(face.cell, face.face_no);
    weights           = follow_segments ? face.nodal_weights.get() : nullptr;
    const auto m_cell = spaces.multiplier_cell(face.cell);
    m_values->reinit(m_cell, face.face_no);
    face.cell->get_dof_indices(u_dofs);
    gather_multipliers(m_cell, face.face_no, ghosted);
    evaluate_multiplier_shapes(nodal_coefficients ? nullptr : face.dual_basis.get());
    evaluate_displacements(ghosted);
  }

  template <int dim>
  void
  FaceEvaluator<dim>::gather_multipliers(
      const typename DoFHandler<dim>::active_cell_iterator &m_cell,
      const unsigned int                                    face_no,
      const TrilinosWrappers::MPI::Vector                  &ghosted)
  {
    std::vector<types::global_dof_index> all_m(spaces.fe_m->n_dofs_per_cell());
    m_cell->get_dof_indices(all_m);
    m_dofs.clear();
    m_local.clear();
    m_coefficients.clear();
    for (const unsigned int i : spaces.multiplier_dofs_on_face[face_no])
      {
        Assert(all_m[i] < spaces.n_multipliers, ExcInternalError());
        m_local.push_back(i);
        m_dofs.push_back(spaces.n_u + all_m[i]);
        m_coefficients.push_back(ghosted(spaces.n_u + all_m[i]));
      }
  }

  template <int dim>
  void
  FaceEvaluator<dim>::evaluate_multiplier_shapes(const FullMatrix<double> *dual)
  {
    // ψ_a at the points: φ_a, or with a dual basis Σ_r A_pr φ_(r, c) (p the
    // node of a, c its component; the nodes in ascending base index)
    const unsigned int n_m = m_local.size();
    m_shapes.reinit(n_m, u_now.size());
    std::vector<unsigned int>              node_of(n_m);
    std::vector<std::vector<unsigned int>> of_node;
    if (dual)
      {
        std::map<unsigned int, unsigned int> position;
        for (const unsigned int i : m_local)
          position.emplace(spaces.fe_m->system_to_component_index(i).second, 0);
        unsigned int p = 0;
        for (auto &entry : position)
          entry.second = p++;
        of_node.assign(position.size(), std::vector<unsigned int>(spaces.fe_m->n_components()));
        for (unsigned int a = 0; a < n_m; ++a)
          {
            const auto [component, base]   = spaces.fe_m->system_to_component_index(m_local[a]);
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
            const unsigned int c     = spaces.fe_m->system_to_component_index(m_local[a]).first;
            double             value = 0.;
            for (unsigned int r = 0; r < of_node.size(); ++r)
              value += (*dual)(node_of[a], r) * m_values->shape_value(m_local[of_node[r][c]], q);
            m_shapes(a, q) = value;
          }
  }

  template <int dim>
  void
  FaceEvaluator<dim>::evaluate_displacements(const TrilinosWrappers::MPI::Vector &ghosted)
  {
    const FiniteElement<dim> &fe = *spaces.fe_u;
    for (unsigned int q = 0; q < u_now.size(); ++q)
      {
        u_now[q]   = 0.;
        u_start[q] = 0.;
        for (unsigned int i = 0; i < u_dofs.size(); ++i)
          {
            const unsigned int c   = fe.system_to_component_index(i).first;
            const double       phi = u_values->shape_value(i, q);
            u_now[q][c] += ghosted(u_dofs[i]) * phi;
            u_start[q][c] += spaces.step_start(u_dofs[i]) * phi;
          }
      }
  }

  template <int dim>
  ContactKinematics<dim>
  FaceEvaluator<dim>::kinematics(const unsigned int q) const
  {
    ContactKinematics<dim> k;
    k.displacement   = u_now[q];
    k.step_increment = u_now[q] - u_start[q];
    k.position       = u_values->quadrature_point(q) + u_now[q];
    k.JxW            = weights ? (*weights)[q]
                               : u_values->JxW(q) * spaces.radial_weight(u_values->quadrature_point(q));
    for (unsigned int a = 0; a < m_local.size(); ++a)
      {
        const unsigned int c = spaces.fe_m->system_to_component_index(m_local[a]).first;
        if (c == 0)
          k.contact_pressure += m_coefficients[a] * m_shapes(a, q);
        else
          k.semi_multiplier[c - 1] += m_coefficients[a] * m_shapes(a, q);
      }
    return k;
  }

  template class FaceEvaluator<2>;
  template class FaceEvaluator<3>;
} // namespace StabilizedLagrangian
