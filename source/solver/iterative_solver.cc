#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <stabilized_lagrangian/solver/iterative_solver.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>
#include <EpetraExt_Transpose_RowMatrix.h>

#include <chrono>
#include <cmath>
#include <map>
#include <numeric>

namespace StabilizedLagrangian
{
  namespace LinearSolvers
  {
    namespace
    {
      /** Wall time (s) since @p start. */
      double
      seconds_since(const std::chrono::steady_clock::time_point start)
      {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }

      /** The place of @p index among the elements of @p set (an element of it). */
      unsigned int
      position(const IndexSet &set, const types::global_dof_index index)
      {
        const unsigned int place = set.index_within_set(index);
        AssertThrow(place != numbers::invalid_unsigned_int, ExcInternalError());
        return place;
      }

      /**
       * @p inverse_diagonal = diag(@p matrix)⁻¹ on the rows @p rows (0 where
       * the diagonal entry is 0).
       */
      void
      invert_diagonal(const TrilinosWrappers::SparseMatrix &matrix,
                      const IndexSet                       &rows,
                      TrilinosWrappers::MPI::Vector        &inverse_diagonal)
      {
        for (const auto i : rows)
          {
            const double diagonal = matrix.diag_element(i);
            inverse_diagonal(i)   = diagonal != 0. ? 1. / diagonal : 0.;
          }
        inverse_diagonal.compress(VectorOperation::insert);
      }

      /** f(row, column, value) for every stored entry of the rows @p rows (locally owned). */
      template <typename Function>
      void
      for_each_entry(const TrilinosWrappers::SparseMatrix &matrix,
                     const IndexSet                       &rows,
                     const Function                       &f)
      {
        const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
        for (const auto row : rows)
          {
            const int local = A.RowMap().LID(static_cast<int>(row));
            if (local < 0)
              continue;
            int     n       = 0;
            double *values  = nullptr;
            int    *indices = nullptr;
            A.ExtractMyRowView(local, n, values, indices);
            for (int k = 0; k < n; ++k)
              f(row, static_cast<types::global_dof_index>(A.ColMap().GID(indices[k])), values[k]);
          }
      }

      /**
       * The block of @p matrix with the rows @p rows and the columns of the
       * displacement (@p u_columns) or of the multipliers, as a matrix of its
       * own on the blocks' numberings: a displacement DoF keeps its index, a
       * multiplier DoF i becomes i − n_u; @p rows, @p domain in those. With
       * @p new_pattern its sparsity pattern is built, else @p block has it
       * from an earlier call and only the values are copied, row by row.
       */
      void
      extract_block(const TrilinosWrappers::SparseMatrix &matrix,
                    const IndexSet                       &rows,
                    const IndexSet                       &domain,
                    const types::global_dof_index         n_u,
                    const bool                            u_rows,
                    const bool                            u_columns,
                    const bool                            new_pattern,
                    const MPI_Comm                        communicator,
                    TrilinosWrappers::SparseMatrix       &block)
      {
        IndexSet monolithic_rows(matrix.m());
        for (const auto row : rows)
          monolithic_rows.add_index(u_rows ? row : row + n_u);
        monolithic_rows.compress();
        const types::global_dof_index row_shift    = u_rows ? 0 : n_u;
        const types::global_dof_index column_shift = u_columns ? 0 : n_u;
        if (new_pattern)
          {
            TrilinosWrappers::SparsityPattern pattern(rows, domain, communicator);
            for_each_entry(
                matrix, monolithic_rows, [&](const auto row, const auto column, const double) {
                  if ((column < n_u) == u_columns)
                    pattern.add(row - row_shift, column - column_shift);
                });
            pattern.compress();
            block.reinit(pattern);
          }
        // the entries of a row arrive together: set them together
        types::global_dof_index              current = numbers::invalid_dof_index;
        std::vector<types::global_dof_index> columns;
        std::vector<double>                  values;
        const auto                           flush = [&]() {
          if (current != numbers::invalid_dof_index && !columns.empty())
            block.set(current - row_shift, columns, values);
          columns.clear();
          values.clear();
        };
        for_each_entry(
            matrix, monolithic_rows, [&](const auto row, const auto column, const double value) {
              if (row != current)
                {
                  flush();
                  current = row;
                }
              if ((column < n_u) == u_columns)
                {
                  columns.push_back(column - column_shift);
                  values.push_back(value);
                }
            });
        flush();
        block.compress(VectorOperation::insert);
      }
    } // namespace

    BlockIterativeSolver::BlockIterativeSolver(
        const IndexSet                         &owned,
        const types::global_dof_index           n_u,
        const MPI_Comm                          communicator,
        const unsigned int                      n_components,
        const std::vector<std::vector<double>> &near_null_space,
        const bool                              higher_order_elements,
        const double                            augmentation_factor,
        const unsigned int                      max_iterations)
        : communicator(communicator)
        , n_u(n_u)
        , owned_u(n_u)
        , owned_m(owned.size() - n_u)
        , n_components(n_components)
        , n_modes(near_null_space.size())
        , higher_order_elements(higher_order_elements)
        , augmentation_factor(augmentation_factor)
        , max_iterations(max_iterations)
    {
      for (const auto index : owned)
        if (index < n_u)
          owned_u.add_index(index);
        else
          owned_m.add_index(index - n_u);
      owned_u.compress();
      owned_m.compress();
      for (const auto &mode : near_null_space)
        {
          Assert(mode.size() == owned_u.n_elements(), ExcInternalError());
          this->near_null_space.insert(this->near_null_space.end(), mode.begin(), mode.end());
        }
      r_u.reinit(owned_u, communicator);
      y_u.reinit(owned_u, communicator);
      r_m.reinit(owned_m, communicator);
      y_m.reinit(owned_m, communicator);
      t_m.reinit(owned_m, communicator);
    }

    BlockIterativeSolver::~BlockIterativeSolver() = default;

    void
    BlockIterativeSolver::set_up(const TrilinosWrappers::SparseMatrix &matrix)
    {
      auto start = std::chrono::steady_clock::now();
      extract_blocks(matrix);
      // diag(K)⁻¹, for the multipliers' compliance with K replaced by its diagonal
      TrilinosWrappers::MPI::Vector inverse_diagonal(owned_u, communicator);
      invert_diagonal(augmented, owned_u, inverse_diagonal);
      augment_displacement_block(inverse_diagonal);
      initialize_amg();
      times.amg_setup = seconds_since(start);
      start           = std::chrono::steady_clock::now();

      schur_factorisation.reset();
      block_rows.clear();
      block_inverses.clear();
      if (owned_m.size() == 0)
        return;
      invert_diagonal(augmented, owned_u, inverse_diagonal);
      form_schur_complement(inverse_diagonal);
      if (invert_local_blocks())
        {
          times.schur = seconds_since(start);
          return;
        }
      schur_factorisation = std::make_unique<TrilinosWrappers::SolverDirect>(
          schur_control, TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Klu"));
      schur_factorisation->initialize(schur);
      times.schur = seconds_since(start);
    }

    void
    BlockIterativeSolver::extract_blocks(const TrilinosWrappers::SparseMatrix &matrix)
    {
      // the Newton matrix keeps its pattern for the life of this solver
      // (ContactProblem makes a new one with each new pattern)
      const bool new_pattern = !blocks_ready;
      extract_block(matrix, owned_u, owned_m, n_u, true, false, new_pattern, communicator, B);
      extract_block(matrix, owned_m, owned_u, n_u, false, true, new_pattern, communicator, C);
      extract_block(matrix, owned_m, owned_m, n_u, false, false, new_pattern, communicator, D);
      if (augmentation_factor > 0.)
        {
          EpetraExt::RowMatrix_Transpose transposer;
          C_transposed.reinit(dynamic_cast<const Epetra_CrsMatrix &>(
              transposer(const_cast<Epetra_CrsMatrix &>(C.trilinos_matrix()))));
        }
      // K is stored only as K̃ = K + Cᵀ Γ C, on the union of K's pattern and
      // Cᵀ C's (made once per pattern); its values first are K's
      if (new_pattern)
        {
          TrilinosWrappers::SparsityPattern pattern(owned_u, owned_u, communicator);
          const auto add_to_pattern = [&](const auto row, const auto column, const double) {
            if (column < n_u)
              pattern.add(row, column);
          };
          for_each_entry(matrix, owned_u, add_to_pattern);
          if (augmentation_factor > 0.)
            {
              TrilinosWrappers::SparseMatrix coupling;
              C_transposed.mmult(coupling, C);
              for_each_entry(coupling, owned_u, add_to_pattern);
            }
          pattern.compress();
          augmented.reinit(pattern);
        }
      augmented = 0.;
      extract_block(matrix, owned_u, owned_u, n_u, true, true, false, communicator, augmented);
      blocks_ready = true;
    }

    void
    BlockIterativeSolver::augment_displacement_block(
        const TrilinosWrappers::MPI::Vector &inverse_diagonal)
    {
      // Γ = c diag(C diag(K)⁻¹ Cᵀ)⁻¹ on the rows that only constrain the
      // displacement, each on its own: D's row vanishes (augmenting rows with D
      // entries too, Γ D ≠ 0, made GMRES stagnate on the patins) and the row of
      // C diag(K)⁻¹ Cᵀ is its diagonal entry (a nodal contact quadrature against
      // a rigid partner; where rows share displacement DoFs, Gauss quadrature or
      // two bodies, augmenting them took more GMRES iterations, not fewer). 0 on
      // the others (an open node's row has C = 0).
      augmentation.reinit(owned_m, communicator);
      if (augmentation_factor > 0.)
        {
          TrilinosWrappers::SparseMatrix compliance;
          C.mmult(compliance, C_transposed, inverse_diagonal);
          std::vector<double> coupling(owned_m.n_elements()), diagonal(owned_m.n_elements());
          for_each_entry(
              compliance, owned_m, [&](const auto row, const auto column, const double value) {
                const unsigned int i = position(owned_m, row);
                if (column == row)
                  diagonal[i] = value;
                else
                  coupling[i] = std::max(coupling[i], std::abs(value));
              });
          std::vector<double> d_row_size(owned_m.n_elements());
          for_each_entry(D, owned_m, [&](const auto row, const auto, const double value) {
            double &size = d_row_size[position(owned_m, row)];
            size         = std::max(size, std::abs(value));
          });
          for (unsigned int i = 0; i < diagonal.size(); ++i)
            if (diagonal[i] > 0. && coupling[i] <= 1e-12 * diagonal[i] && d_row_size[i] == 0.)
              augmentation(owned_m.nth_index_in_set(i)) = augmentation_factor / diagonal[i];
        }
      augmentation.compress(VectorOperation::insert);
      if (augmentation.linfty_norm() > 0.)
        {
          TrilinosWrappers::SparseMatrix penalty;
          C_transposed.mmult(penalty, C, augmentation);
          augmented.add(1., penalty);
        }
    }

    void
    BlockIterativeSolver::initialize_amg()
    {
      // smoothed aggregation with the given near-null space (translations, or
      // all rigid-body modes), aggregating whole nodes
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = higher_order_elements;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.02;
      // (no constant modes given: the library's defaults, then the near-null space set here)
      Teuchos::ParameterList              parameters;
      std::unique_ptr<Epetra_MultiVector> unused_modes;
      data.set_parameters(parameters, unused_modes, augmented);
      parameters.set("null space: type", "pre-computed");
      parameters.set("null space: dimension", static_cast<int>(n_modes));
      parameters.set("null space: vectors", const_cast<double *>(near_null_space.data()));
      // (the DoFs of a node are consecutive: aggregate nodes, not single DoFs)
      parameters.set("PDE equations", static_cast<int>(n_components));
      amg.initialize(augmented, parameters);
    }

    void
    BlockIterativeSolver::form_schur_complement(
        const TrilinosWrappers::MPI::Vector &inverse_diagonal)
    {
      // Ŝ = D − C diag(K̃)⁻¹ B (Γ D = 0: B + Cᵀ Γ D = B), on the union of the patterns
      TrilinosWrappers::SparseMatrix product;
      C.mmult(product, B, inverse_diagonal);
      TrilinosWrappers::SparsityPattern pattern(owned_m, owned_m, communicator);
      const auto add_to_pattern = [&](const auto row, const auto column, const double) {
        pattern.add(row, column);
      };
      for_each_entry(D, owned_m, add_to_pattern);
      for_each_entry(product, owned_m, add_to_pattern);
      pattern.compress();
      schur.reinit(pattern);
      for_each_entry(D, owned_m, [&](const auto row, const auto column, const double value) {
        schur.add(row, column, value);
      });
      for_each_entry(product, owned_m, [&](const auto row, const auto column, const double value) {
        schur.add(row, column, -value);
      });
      schur.compress(VectorOperation::add);
    }

    bool
    BlockIterativeSolver::invert_local_blocks()
    {
      // the connected components of Ŝ's graph over the owned rows (union–find)
      constexpr unsigned int    largest_block = 64;
      const unsigned int        n_rows        = owned_m.n_elements();
      std::vector<unsigned int> root(n_rows);
      std::iota(root.begin(), root.end(), 0u);
      const auto find = [&root](unsigned int i) {
        while (root[i] != i)
          i = root[i] = root[root[i]];
        return i;
      };
      // (the pattern holds every pair of DoFs of a contact face: an entry
      // couples two rows only where its value does, beyond round-off of the row)
      std::vector<double> row_size(n_rows);
      for_each_entry(schur, owned_m, [&](const auto row, const auto, const double value) {
        double &size = row_size[position(owned_m, row)];
        size         = std::max(size, std::abs(value));
      });
      int local = 1;
      for_each_entry(schur, owned_m, [&](const auto row, const auto column, const double value) {
        if (std::abs(value) <= 1e-12 * row_size[position(owned_m, row)])
          return;
        if (!owned_m.is_element(column))
          local = 0;
        else
          root[find(position(owned_m, row))] = find(position(owned_m, column));
      });
      std::map<unsigned int, std::vector<unsigned int>> components;
      if (local == 1)
        for (unsigned int i = 0; i < n_rows; ++i)
          {
            auto &rows = components[find(i)];
            rows.push_back(i);
            if (rows.size() > largest_block)
              local = 0;
          }
      if (Utilities::MPI::min(local, communicator) == 0)
        return false;

      std::vector<unsigned int> place(n_rows);
      for (const auto &[component, rows] : components)
        {
          for (unsigned int a = 0; a < rows.size(); ++a)
            place[rows[a]] = a;
          block_rows.push_back(rows);
          block_inverses.emplace_back(rows.size(), rows.size());
        }
      std::vector<unsigned int> block_of(n_rows);
      for (unsigned int b = 0; b < block_rows.size(); ++b)
        for (const unsigned int i : block_rows[b])
          block_of[i] = b;
      for_each_entry(schur, owned_m, [&](const auto row, const auto column, const double value) {
        const unsigned int i = position(owned_m, row);
        if (std::abs(value) <= 1e-12 * row_size[i])
          return;
        const unsigned int j = position(owned_m, column);
        block_inverses[block_of[i]](place[i], place[j]) += value;
      });
      for (auto &block : block_inverses)
        block.gauss_jordan();
      return true;
    }

    void
    BlockIterativeSolver::vmult(TrilinosWrappers::MPI::Vector       &dst,
                                const TrilinosWrappers::MPI::Vector &src) const
    {
      // P [y_u; y_m] = [r_u; r_m]: Ŝ y_m = r_m, then K̂ y_u = r_u − B y_m. The
      // owned rows of the whole system are the owned u rows, then the owned
      // multiplier rows, both ascending: the blocks are slices of the local array.
      const unsigned int n_owned_u = owned_u.n_elements();
      const double      *source    = src.trilinos_vector()[0];
      const double      *unweight  = inverse_weights.trilinos_vector()[0];
      double            *ru = r_u.trilinos_vector()[0], *rm = r_m.trilinos_vector()[0];
      for (unsigned int k = 0; k < n_owned_u; ++k)
        ru[k] = source[k] * unweight[k];
      for (unsigned int k = 0; k < owned_m.n_elements(); ++k)
        rm[k] = source[n_owned_u + k] * unweight[n_owned_u + k];
      if (!block_rows.empty())
        {
          const auto start = std::chrono::steady_clock::now();
          double    *ym    = y_m.trilinos_vector()[0];
          for (unsigned int b = 0; b < block_rows.size(); ++b)
            {
              const auto &rows = block_rows[b];
              for (unsigned int a = 0; a < rows.size(); ++a)
                {
                  double sum = 0.;
                  for (unsigned int c = 0; c < rows.size(); ++c)
                    sum += block_inverses[b](a, c) * rm[rows[c]];
                  ym[rows[a]] = sum;
                }
            }
          times.schur_solves += seconds_since(start);
        }
      else if (schur_factorisation)
        {
          const auto start = std::chrono::steady_clock::now();
          schur_factorisation->solve(y_m, r_m);
          times.schur_solves += seconds_since(start);
        }
      // K̃ y_u = r_u + Cᵀ Γ r_m − (B + Cᵀ Γ D) y_m = r_u − B y_m + Cᵀ Γ r_m
      B.vmult(y_u, y_m);
      r_u -= y_u;
      if (augmentation_factor > 0.)
        {
          t_m = r_m;
          t_m.scale(augmentation);
          C_transposed.vmult(y_u, t_m);
          r_u += y_u;
        }
      amg.vmult(y_u, r_u);
      double       *destination = dst.trilinos_vector()[0];
      const double *yu = y_u.trilinos_vector()[0], *ym = y_m.trilinos_vector()[0];
      for (unsigned int k = 0; k < n_owned_u; ++k)
        destination[k] = yu[k];
      for (unsigned int k = 0; k < owned_m.n_elements(); ++k)
        destination[n_owned_u + k] = ym[k];
    }

    namespace
    {
      /** W J: the Newton matrix with its rows weighted. */
      struct WeightedOperator
      {
        const TrilinosWrappers::SparseMatrix &matrix;
        const TrilinosWrappers::MPI::Vector  &weights;
        void
        vmult(TrilinosWrappers::MPI::Vector &dst, const TrilinosWrappers::MPI::Vector &src) const
        {
          matrix.vmult(dst, src);
          dst.scale(weights);
        }
      };
    } // namespace

    bool
    BlockIterativeSolver::solve(const TrilinosWrappers::SparseMatrix &matrix,
                                TrilinosWrappers::MPI::Vector        &x,
                                const TrilinosWrappers::MPI::Vector  &b,
                                const TrilinosWrappers::MPI::Vector  &row_weights,
                                const double                          relative_tolerance)
    {
      error.clear();
      iterations = 0;
      times      = PhaseTimes();
      // a Trilinos error in the set-up (ML's aggregation, the Schur
      // complement's factorisation) fails this solve, which the direct solver
      // then takes over, instead of ending the run
      try
        {
          set_up(matrix);
        }
      catch (const std::exception &failure)
        {
          blocks_ready = false;
          error        = std::string("the preconditioner's set-up failed: ") + failure.what();
          return false;
        }
      const auto start = std::chrono::steady_clock::now();
      // (on every exit)
      const auto account = [&]() { times.krylov = seconds_since(start); };
      x                  = 0.;
      // GMRES on W J x = W b, W the rows' weights, preconditioned by (W P)⁻¹ = P⁻¹ W⁻¹:
      // its residual is the weighted one the Newton criterion measures
      inverse_weights.reinit(row_weights);
      for (unsigned int k = 0; k < inverse_weights.locally_owned_size(); ++k)
        inverse_weights.trilinos_vector()[0][k] = 1. / row_weights.trilinos_vector()[0][k];
      TrilinosWrappers::MPI::Vector weighted_b(b);
      weighted_b.scale(row_weights);
      const double target = relative_tolerance * weighted_b.l2_norm();
      if (target == 0.)
        return true;
      SolverControl control(max_iterations, target, false, false);
      SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData data(100, true);
      SolverGMRES<TrilinosWrappers::MPI::Vector>                 gmres(control, data);
      try
        {
          gmres.solve(WeightedOperator{matrix, row_weights}, x, weighted_b, *this);
        }
      catch (const SolverControl::NoConvergence &failure)
        {
          account();
          iterations = failure.last_step;
          error      = "GMRES did not reach the relative residual " +
                  std::to_string(relative_tolerance) + " in " + std::to_string(max_iterations) +
                  " iterations (last " +
                  std::to_string(failure.last_residual / weighted_b.l2_norm()) + ")";
          return false;
        }
      catch (const std::exception &failure)
        {
          account();
          error = std::string("GMRES failed: ") + failure.what();
          return false;
        }
      account();
      iterations = control.last_step();
      if (!std::isfinite(x.linfty_norm()))
        {
          error = "GMRES returned a solution that is not finite";
          return false;
        }
      return true;
    }
  } // namespace LinearSolvers
} // namespace StabilizedLagrangian
