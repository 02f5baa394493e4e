#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/full_matrix.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace StabilizedLagrangian
{
  namespace BoundaryConditions
  {
    /**
     * @brief A rigid plate tied to a boundary (doc/formulation.md, "Rigid
     * plates"): the boundary's displacement in the plate's components is one
     * translation U (a guided plate), or U + θ × (X − X_0) (a plate free to
     * turn, every component tied), and the plate carries a resultant force
     * F(t) at X_0. Built as multi-point constraints on its reference DoFs.
     */
    template <int dim> class RigidPlate : public OnBoundary<dim>
    {
    public:
      RigidPlate(ParameterHandler &prm, const std::string &section)
          : OnBoundary<dim>(prm, section, OnBoundary<dim>::Role::linked)
      {
        if (!this->used())
          return;
        std::vector<bool> mask(dim, false);
        for (const auto &c : Utilities::split_string_list(prm.get("Components")))
          mask[c == "x" ? 0 : (c == "y" ? 1 : 2)] = true;
        if (std::none_of(mask.begin(), mask.end(), [](const bool b) { return b; }))
          throw InputError(section +
                           "/Components: empty, so the plate ties nothing; name the "
                           "components it carries (x, y" +
                           std::string(dim == 3 ? ", z" : "") + ").");
        free_rotation = prm.get("Rotation") == "free";
        if (free_rotation && std::count(mask.begin(), mask.end(), true) != dim)
          throw InputError(section +
                           "/Rotation = free: a plate free to turn ties every component; "
                           "set Components = " +
                           std::string(dim == 2 ? "x, y" : "x, y, z") + ".");
        components      = ComponentMask(mask);
        force           = Parameters::parse_function<dim>(prm, section, "Force");
        reference_point = parse_point<dim>(prm, section, "Reference point", "a point");
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        OnBoundary<dim>::declare_boundary(
            prm,
            "tied to a rigid plate: in the plate's components it moves as one "
            "translation, and turns with the plate if Rotation = free");
        prm.declare_entry("Components",
                          dim == 2 ? "y" : "z",
                          Patterns::MultipleSelection(dim == 2 ? "x|y" : "x|y|z"),
                          "The components the plate ties; the others stay free (or take "
                          "another condition).");
        prm.declare_entry("Rotation",
                          "guided",
                          Patterns::Selection("guided|free"),
                          "guided: the plate only translates; free: it also turns (a "
                          "small rotation theta about the reference point, u = U + theta x "
                          "(X - X_0)), carrying the force at the reference point and no "
                          "moment; needs every component tied.");
        prm.declare_entry("Reference point",
                          "",
                          Patterns::Anything(),
                          "X_0 (mm): where the force acts and the plate turns about; "
                          "empty: the centroid of the boundary's nodes.");
        prm.enter_subsection("Force");
        Parameters::declare_function<dim>(prm, "N, per mm of thickness in 2D; only t is used");
        prm.leave_subsection();
      }

      void
      find_linked_dofs(const Problem<dim>                                 &problem,
                       const std::vector<std::unique_ptr<Interface<dim>>> &conditions,
                       IndexSet                                           &relevant) override
      {
        if (free_rotation && problem.axisymmetric)
          throw InputError(this->section() +
                           "/Rotation = free: an axisymmetric model has no rotation to free; "
                           "use guided.");
        refuse_shared_nodes(problem, conditions);
        // the candidates: the owned DoFs of the tied components that do not hang
        const IndexSet hanging = DoFTools::extract_hanging_node_dofs(problem.dof_handler);
        Candidates     candidates;
        for_each_dof(problem, false, [&](const auto dof, const unsigned int c, const auto &X) {
          if (problem.locally_owned_u.is_element(dof) && !hanging.is_element(dof))
            candidates.emplace(dof, std::make_pair(c, X));
        });
        if (Utilities::MPI::sum(candidates.size(), problem.communicator) == 0)
          throw InputError(this->section() + "/Boundary id: the boundary has no node to tie.");

        motion = Motion();
        for (unsigned int c = 0; c < dim; ++c)
          if (components[c])
            motion.modes.push_back(c);
        for (unsigned int axis = 0; axis < n_rotations(); ++axis)
          motion.modes.push_back(dim + axis);
        place(problem.communicator, candidates);
        choose_reference_dofs(problem.communicator, candidates);
        // every rank couples to the reference DoFs
        for (const auto dof : motion.dofs)
          relevant.add_index(dof);
      }

      std::optional<IndexSet>
      linked_boundary_dofs(const Problem<dim> &problem, const unsigned int c) const override
      {
        if (!components[c])
          return std::nullopt;
        return boundary_component_dofs(problem.dof_handler, this->boundary_id, c);
      }

      void
      add_linked_constraints(const Problem<dim>        &problem,
                             AffineConstraints<double> &constraints) const override
      {
        // u_i = Σ_k C_ik u_{r_k} (Motion::coefficients()); hanging nodes follow
        // their parents, which are tied
        for_each_dof(problem, true, [&](const auto dof, const unsigned int c, const auto &X) {
          if (constraints.is_constrained(dof) || !constraints.can_store_line(dof) ||
              std::find(motion.dofs.begin(), motion.dofs.end(), dof) != motion.dofs.end())
            return;
          const Vector<double> C = motion.coefficients(X, c);
          constraints.add_line(dof);
          for (unsigned int k = 0; k < C.size(); ++k)
            if (std::abs(C[k]) > 1e-14)
              constraints.add_entry(dof, motion.dofs[k], C[k]);
        });
      }

      void
      check_prescribed_vertex(const Problem<dim>   &problem,
                              const Interface<dim> &other) const override
      {
        // a node held by a point condition and tied to the plate would hold the
        // plate by that node alone: the plate's load would go partly into the
        // point's reaction
        for (unsigned int c = 0; c < dim; ++c)
          if (const auto dof = other.prescribed_point_dof(c); dof && components[c])
            {
              const bool shared = boundary_component_dofs(problem.dof_handler, this->boundary_id, c)
                                      .is_element(*dof);
              if (Utilities::MPI::logical_or(shared, problem.communicator))
                throw InputError(other.section() + ": its point is a node of " + this->section() +
                                 " in component " + "xyz"[c] +
                                 ", which would hold the plate by that node and take part of "
                                 "its load; leave that component out of one of them.");
            }
      }

      void
      assemble_global(const Problem<dim> &problem,
                      const AffineConstraints<double> &,
                      TrilinosWrappers::MPI::Vector &system_rhs,
                      TrilinosWrappers::MPI::Vector &external_force) const override
      {
        // F acts on the plate at X_0: its virtual work F·δU = g·δq with g the
        // force's components on the translation parameters (0 on the rotation's:
        // no moment), i.e. A_R⁻ᵀ g on the reference DoFs, into whose rows the
        // constraints sum the tied DoFs' equations
        const Vector<double> value = value_at_time(*force, problem.time);
        force->check_finite(problem.communicator);
        const unsigned int m = motion.modes.size();
        Vector<double>     g(m), on_reference(m);
        for (unsigned int k = 0; k < m; ++k)
          if (motion.modes[k] < dim)
            g[k] = value(motion.modes[k]);
        motion.inverse.Tvmult(on_reference, g);
        for (unsigned int k = 0; k < m; ++k)
          if (problem.locally_owned.is_element(motion.dofs[k]))
            {
              system_rhs(motion.dofs[k]) -= on_reference[k];
              external_force(motion.dofs[k]) += on_reference[k];
            }
      }

      /** @brief The tied components take the plate's distributed reaction. */
      void
      hold_components(const types::boundary_id id, std::vector<bool> &free) const override
      {
        if (id == this->boundary_id)
          for (unsigned int d = 0; d < dim; ++d)
            free[d] = free[d] && !components[d];
      }

      /**
       * @brief plate_<name>_{displacement_<axis>_mm,force_<axis>_N}, and, free
       * to turn, plate_<name>_rotation_rad (2D) or _rotation_<axis>_rad (3D)
       * after every plate's translation and force (group 1).
       */
      void
      add_statistics_columns(StatisticsWriter::Supports &supports) const override
      {
        const std::string plate = "plate_" + name();
        for (unsigned int d = 0; d < dim; ++d)
          {
            const std::string axis(1, "xyz"[d]);
            supports.condition_columns.push_back({plate + "_displacement_" + axis + "_mm", 0});
            supports.condition_columns.push_back(
                {plate + "_force_" + axis + "_" + supports.force_unit, 0});
          }
        for (unsigned int a = 0; a < n_rotations(); ++a)
          supports.condition_columns.push_back(
              {plate + "_rotation_" +
                   (n_rotations() == 1 ? std::string() : std::string(1, "xyz"[a]) + "_") + "rad",
               1});
      }

      /** @brief Its translation U, force F(t) and rotation θ (collective). */
      void
      add_statistics(const Problem<dim>        &problem,
                     const ReactionInputs<dim> &inputs,
                     StepStatistics            &stats) const override
      {
        const Vector<double> value = value_at_time(*force, problem.time);
        // the parameters q = A_R⁻¹ u_R: U, and θ scaled by the plate's size
        const TrilinosWrappers::MPI::Vector &u = inputs.displacement();
        const unsigned int                   m = motion.modes.size();
        Vector<double>                       reference(m), q(m);
        for (unsigned int k = 0; k < m; ++k)
          if (problem.locally_owned.is_element(motion.dofs[k]))
            reference[k] = u(motion.dofs[k]);
        Utilities::MPI::sum(ArrayView<const double>(reference.begin(), m),
                            problem.communicator,
                            ArrayView<double>(reference.begin(), m));
        motion.inverse.vmult(q, reference);
        std::array<double, 3> displacement = {{0., 0., 0.}}, applied = {{0., 0., 0.}},
                              rotation = {{0., 0., 0.}};
        for (unsigned int k = 0; k < m; ++k)
          if (motion.modes[k] < dim)
            {
              displacement[motion.modes[k]] = q[k];
              applied[motion.modes[k]]      = value(motion.modes[k]);
            }
          else
            rotation[motion.modes[k] - dim] = q[k] / motion.size;
        for (unsigned int d = 0; d < dim; ++d)
          {
            stats.condition_values.push_back(displacement[d]);
            stats.condition_values.push_back(applied[d]);
          }
        for (unsigned int a = 0; a < n_rotations(); ++a)
          stats.condition_values.push_back(rotation[a]);
      }

    private:
      /**
       * The plate's motion u(X) = U + θ × (X − X_0), linear in its parameters q
       * (the tied components of U; with `Rotation = free` also θ, scaled by the
       * plate's size): u at a DoF in component c at X is a(X, c)·q. The
       * plate's DoFs follow the values of m reference DoFs r_k, q = A_R⁻¹ u_R
       * with A_R the rows a of the reference DoFs.
       */
      struct Motion
      {
        /** the parameters: 0..dim−1 the translation's components, dim.. the rotation's */
        std::vector<unsigned int> modes;
        /** the reference DoFs r_k, one per parameter */
        std::vector<types::global_dof_index> dofs;
        /** A_R⁻¹: the parameters from the reference DoFs' values */
        FullMatrix<double> inverse;
        /** X_0, where the force acts and θ turns about, and the length the rotation is scaled by */
        Point<dim> point;
        double     size = 1.;

        /** a(X, c): the displacement in component @p c at @p X per parameter */
        Vector<double>
        row(const Point<dim> &X, const unsigned int c) const
        {
          const Tensor<1, dim> r = (X - point) / size;
          Vector<double>       a(modes.size());
          for (unsigned int k = 0; k < modes.size(); ++k)
            if (modes[k] < dim)
              a[k] = modes[k] == c ? 1. : 0.;
            else if constexpr (dim == 2)
              a[k] = c == 0 ? -r[1] : r[0]; // θ e_z × r
            else
              {
                // (e_axis × r)_c
                Tensor<1, 3> axis, rr;
                axis[modes[k] - dim] = 1.;
                for (unsigned int d = 0; d < 3; ++d)
                  rr[d] = r[d];
                a[k] = cross_product_3d(axis, rr)[c];
              }
          return a;
        }

        /** C_i = A_R⁻ᵀ a(X, c): the DoF at @p X in component @p c is Σ_k C_ik u_{r_k} */
        Vector<double>
        coefficients(const Point<dim> &X, const unsigned int c) const
        {
          Vector<double> C(modes.size());
          inverse.Tvmult(C, row(X, c));
          return C;
        }
      };

      /** the candidates for reference DoFs, with their component and support point */
      using Candidates = std::map<types::global_dof_index, std::pair<unsigned int, Point<dim>>>;

      /** the subsection's name, for the columns: `Rigid plate <name>` */
      std::string
      name() const
      {
        return this->section().substr(std::string("Boundary conditions/Rigid plate ").size());
      }

      /** the number of rotation parameters: 0 guided, 1 in 2D, 3 in 3D */
      unsigned int
      n_rotations() const
      {
        return free_rotation ? (dim == 2 ? 1 : 3) : 0;
      }

      /**
       * Calls @p f(dof, component, support point) for the DoFs of the tied
       * components on the boundary of the locally owned (and, with @p
       * with_ghosts, ghost) cells, once per cell that has them.
       */
      template <typename Function>
      void
      for_each_dof(const Problem<dim> &problem, const bool with_ghosts, const Function &f) const
      {
        const FiniteElement<dim>            &fe = problem.fe;
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        for (const auto &cell : problem.dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() || (with_ghosts && cell->is_ghost()))
            for (const unsigned int face : cell->face_indices())
              if (cell->face(face)->at_boundary() &&
                  cell->face(face)->boundary_id() == this->boundary_id)
                {
                  cell->get_dof_indices(dofs);
                  const auto &mapping =
                      cell->reference_cell().template get_default_linear_mapping<dim>();
                  for (unsigned int i = 0; i < dofs.size(); ++i)
                    if (fe.has_support_on_face(i, face))
                      {
                        const unsigned int c = fe.system_to_component_index(i).first;
                        if (components[c])
                          f(dofs[i],
                            c,
                            mapping.transform_unit_to_real_cell(cell, fe.unit_support_point(i)));
                      }
                }
      }

      /**
       * Refuse a boundary that shares nodes, in a tied component, with one a
       * condition prescribes (the plate would be held) or one an earlier
       * condition links (a node cannot follow two plates).
       */
      void
      refuse_shared_nodes(const Problem<dim>                                 &problem,
                          const std::vector<std::unique_ptr<Interface<dim>>> &conditions) const
      {
        for (unsigned int c = 0; c < dim; ++c)
          if (components[c])
            {
              const IndexSet tied =
                  boundary_component_dofs(problem.dof_handler, this->boundary_id, c);
              const auto refuse_shared = [&](const IndexSet       &other,
                                             const Interface<dim> &condition,
                                             const std::string    &why) {
                const bool shared = !(tied & other & problem.locally_owned_u).is_empty();
                if (Utilities::MPI::logical_or(shared, problem.communicator))
                  throw InputError(this->section() + ": its boundary shares nodes with " +
                                   condition.section() + " in component " + "xyz"[c] + why);
              };
              for (const auto &condition : conditions)
                if (const auto held = condition->prescribed_boundary_dofs(problem, c))
                  refuse_shared(*held,
                                *condition,
                                ", which would hold the plate; leave that component out of "
                                "one of them.");
              // a node tied to two plates would make them one (each plate's
              // motion is its reference DoFs, which that node cannot follow twice)
              for (const auto &condition : conditions)
                {
                  if (condition.get() == this)
                    break;
                  if (const auto linked = condition->linked_boundary_dofs(problem, c))
                    refuse_shared(*linked,
                                  *condition,
                                  " (a node of both, such as a shared corner, cannot follow "
                                  "two plates); leave that component out of one of them, or "
                                  "make the two boundaries one plate.");
                }
            }
      }

      /**
       * X_0: given, or the centroid of the boundary's nodes; the size: the
       * largest distance of a node from it.
       */
      void
      place(const MPI_Comm communicator, const Candidates &candidates)
      {
        double     count = 0.;
        Point<dim> sum;
        for (const auto &[dof, where] : candidates)
          if (where.first == motion.modes[0])
            {
              sum += where.second;
              count += 1.;
            }
        count = Utilities::MPI::sum(count, communicator);
        const Tensor<1, dim> centroid =
            Utilities::MPI::sum(static_cast<const Tensor<1, dim> &>(sum), communicator) / count;
        motion.point = reference_point ? *reference_point : Point<dim>(centroid);
        double size  = 0.;
        for (const auto &[dof, where] : candidates)
          size = std::max(size, where.second.distance(motion.point));
        motion.size = std::max(Utilities::MPI::max(size, communicator), 1e-300);
      }

      /**
       * The reference DoFs, by a pivoted Gram–Schmidt over the candidates'
       * rows: each takes the largest part of its row the chosen ones do not
       * span (ties to the smallest index, so the choice does not depend on the
       * partition); and A_R⁻¹.
       */
      void
      choose_reference_dofs(const MPI_Comm communicator, const Candidates &candidates)
      {
        const unsigned int          m = motion.modes.size();
        std::vector<Vector<double>> basis;
        FullMatrix<double>          A(m, m);
        for (unsigned int k = 0; k < m; ++k)
          {
            std::vector<double> best = {-1., 0.};
            for (const auto &[dof, where] : candidates)
              {
                Vector<double> a = motion.row(where.second, where.first);
                for (const auto &q : basis)
                  a.add(-(a * q), q);
                if (a.l2_norm() > best[0] * (1. + 1e-12))
                  best = {a.l2_norm(), static_cast<double>(dof)};
              }
            double                  chosen_norm = 0.;
            types::global_dof_index chosen      = numbers::invalid_dof_index;
            for (const auto &other : Utilities::MPI::all_gather(communicator, best))
              if (other[0] > chosen_norm * (1. + 1e-12) ||
                  (other[0] >= chosen_norm * (1. - 1e-12) && other[0] > 0. &&
                   static_cast<types::global_dof_index>(other[1]) < chosen))
                {
                  chosen_norm = other[0];
                  chosen      = static_cast<types::global_dof_index>(other[1]);
                }
            if (chosen_norm < 1e-6)
              throw InputError(this->section() +
                               "/Rotation = free: the boundary's nodes do not fix the plate's "
                               "rotation (they lie on one line); tie a boundary that spans "
                               "the plate, or use guided.");
            // every rank: the chosen DoF's row, from its owner
            Vector<double> a(m);
            if (candidates.count(chosen) > 0)
              a = motion.row(candidates.at(chosen).second, candidates.at(chosen).first);
            Utilities::MPI::sum(ArrayView<const double>(a.begin(), m),
                                communicator,
                                ArrayView<double>(a.begin(), m));
            for (unsigned int j = 0; j < m; ++j)
              A(k, j) = a[j];
            motion.dofs.push_back(chosen);
            for (const auto &q : basis)
              a.add(-(a * q), q);
            a /= a.l2_norm();
            basis.push_back(a);
          }
        motion.inverse.reinit(m, m);
        motion.inverse.invert(A);
      }

      ComponentMask components;                                 ///< the components tied to U
      bool          free_rotation = false;                      ///< `Rotation = free`
      std::shared_ptr<Parameters::BoundaryFunction<dim>> force; ///< F(t), N (N/mm in 2D)
      std::optional<Point<dim>> reference_point; ///< X_0; none: the boundary's centroid
      Motion                    motion;          ///< found on each new mesh
    };

    SL_REGISTER_BOUNDARY_CONDITION(RigidPlate, "Rigid plate", "a plate carrying a force");
  } // namespace BoundaryConditions
} // namespace StabilizedLagrangian
