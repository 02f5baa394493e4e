#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <deal.II/numerics/vector_tools.h>

#include <stabilized_lagrangian/solver/inf_sup_test.h>
#include <stabilized_lagrangian/solver/linear_solver.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>

namespace StabilizedLagrangian
{
  namespace
  {
    /**
     * The smallest eigenvalue of Pᵀ S P x = β² Pᵀ M P x: the Schur complement
     * and the multiplier Gram matrix restricted to the free multipliers
     * (hanging nodes and a coarser multiplier mesh constrain the others, μ = P μ_free).
     */
    double
    smallest_generalized_eigenvalue(const FullMatrix<double> &schur,
                                    const FullMatrix<double> &gram_m,
                                    const FullMatrix<double> &prolongation)
    {
      const unsigned int n_free = prolongation.n();
      const auto restrict       = [&](const FullMatrix<double> &full) {
        FullMatrix<double> result(n_free, n_free);
        result.triple_product(full, prolongation, prolongation, true, false);
        LAPACKFullMatrix<double> lapack(n_free, n_free);
        lapack = result;
        return lapack;
      };
      LAPACKFullMatrix<double>    schur_free = restrict(schur);
      LAPACKFullMatrix<double>    gram_free  = restrict(gram_m);
      std::vector<Vector<double>> eigenvectors(n_free, Vector<double>(n_free));
      schur_free.compute_generalized_eigenvalues_symmetric(gram_free, eigenvectors);
      double smallest = std::numeric_limits<double>::max();
      for (unsigned int k = 0; k < n_free; ++k)
        smallest = std::min(smallest, schur_free.eigenvalue(k).real());
      return smallest;
    }
  } // namespace

  template <int dim>
  InfSupTest<dim>::InfSupTest(const MPI_Comm             communicator,
                              const Parameters::Contact &contact,
                              const ConditionalOStream  &pcout)
      : communicator(communicator)
      , pcout(pcout)
      , fe_pair(contact.fe_pair)
      , check_asked(contact.check_inf_sup)
      , one_rank(Utilities::MPI::n_mpi_processes(communicator) == 1)
  {
  }

  template <int dim>
  InfSupRecord
  InfSupTest<dim>::compute(const View &view) const
  {
    AssertThrow(Utilities::MPI::n_mpi_processes(view.communicator) == 1,
                ExcMessage("The inf-sup test runs on one MPI rank."));

    // K: H¹ Gram matrix of the displacement, Dirichlet DoFs constrained
    AffineConstraints<double> constraints(view.locally_relevant_u);
    DoFTools::make_hanging_node_constraints(view.displacement_dofs, constraints);
    view.add_dirichlet_constraints(constraints);
    constraints.close();
    TrilinosWrappers::SparseMatrix gram_u;
    assemble_h1_gram(view, constraints, gram_u);

    // B (rows: the λ_n DoFs) and M
    std::map<types::global_dof_index, unsigned int> normal_row;
    for (const auto &[row, component] : view.multiplier_components)
      if (component == 0)
        normal_row.emplace(row, normal_row.size());
    const unsigned int                         n_rows = normal_row.size();
    std::vector<TrilinosWrappers::MPI::Vector> trace_rows(
        n_rows, TrilinosWrappers::MPI::Vector(view.locally_owned_u, view.communicator));
    FullMatrix<double> gram_m(n_rows, n_rows);
    const double       contact_mesh_size =
        assemble_trace_pairing(view, constraints, normal_row, trace_rows, gram_m);

    // S = B K⁻¹ Bᵀ, one solve per multiplier row
    LinearSolvers::DirectSolver   solver(view.direct_solver);
    FullMatrix<double>            schur(n_rows, n_rows);
    TrilinosWrappers::MPI::Vector lifted(view.locally_owned_u, view.communicator);
    for (unsigned int a = 0; a < n_rows; ++a)
      {
        trace_rows[a].compress(VectorOperation::add);
        AssertThrow(solver.solve(gram_u, lifted, trace_rows[a]),
                    ExcMessage("The inf-sup test could not factorise the H1 Gram matrix."));
        for (unsigned int b = 0; b <= a; ++b)
          schur(a, b) = schur(b, a) = lifted * trace_rows[b];
      }

    const FullMatrix<double> prolongation = multiplier_prolongation(view, normal_row);
    const double smallest = smallest_generalized_eigenvalue(schur, gram_m, prolongation);
    InfSupRecord record;
    record.contact_mesh_size      = contact_mesh_size;
    record.displacement_dofs      = view.n_displacement_dofs;
    record.normal_multiplier_dofs = prolongation.n();
    record.beta                   = std::sqrt(std::max(smallest, 0.));
    return record;
  }

  template <int dim>
  void
  InfSupTest<dim>::assemble_h1_gram(const View                      &view,
                                    const AffineConstraints<double> &constraints,
                                    TrilinosWrappers::SparseMatrix  &gram_u)
  {
    DynamicSparsityPattern dsp(view.locally_relevant_u);
    DoFTools::make_sparsity_pattern(view.displacement_dofs, dsp, constraints, false);
    gram_u.reinit(view.locally_owned_u, view.locally_owned_u, dsp, view.communicator);

    const FiniteElement<dim> &fe              = view.displacement_fe;
    const Quadrature<dim>    &cell_quadrature = view.cell_quadrature;
    FEValues<dim>             fe_values(
        fe, cell_quadrature, update_values | update_gradients | update_JxW_values);
    const unsigned int        n_dofs = fe.n_dofs_per_cell();
    std::vector<unsigned int> component(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      component[i] = fe.system_to_component_index(i).first;
    FullMatrix<double>                   cell_matrix(n_dofs, n_dofs);
    std::vector<types::global_dof_index> dofs(n_dofs);
    for (const auto &cell : view.displacement_dofs.active_cell_iterators())
      {
        fe_values.reinit(cell);
        cell_matrix = 0.;
        for (unsigned int q = 0; q < cell_quadrature.size(); ++q)
          for (unsigned int i = 0; i < n_dofs; ++i)
            for (unsigned int j = 0; j < n_dofs; ++j)
              if (component[i] == component[j])
                cell_matrix(i, j) += (fe_values.shape_grad(i, q) * fe_values.shape_grad(j, q) +
                                      fe_values.shape_value(i, q) * fe_values.shape_value(j, q)) *
                                     fe_values.JxW(q);
        cell->get_dof_indices(dofs);
        constraints.distribute_local_to_global(cell_matrix, dofs, gram_u);
      }
    gram_u.compress(VectorOperation::add);
  }

  template <int dim>
  double
  InfSupTest<dim>::assemble_trace_pairing(
      const View                                            &view,
      const AffineConstraints<double>                       &constraints,
      const std::map<types::global_dof_index, unsigned int> &normal_row,
      std::vector<TrilinosWrappers::MPI::Vector>            &trace_rows,
      FullMatrix<double>                                    &gram_m)
  {
    const Quadrature<dim - 1> &quadrature = view.trace_quadrature;
    const FiniteElement<dim>  &fe_u       = view.displacement_fe;
    const unsigned int         n_dofs     = fe_u.n_dofs_per_cell();
    std::vector<unsigned int>  component(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      component[i] = fe_u.system_to_component_index(i).first;
    FaceEvaluator  evaluator(view.spaces, quadrature, false);
    Vector<double> cell_row(n_dofs);
    double         contact_mesh_size = 0.;
    for (const auto &face : view.contact.faces())
      {
        evaluator.reinit(face, view.ghosted_solution);
        const double h    = face.cell->face(face.face_no)->diameter();
        contact_mesh_size = std::max(contact_mesh_size, h);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            const Tensor<1, dim> normal =
                view.partner.project(evaluator.u_values->quadrature_point(q)).normal;
            const double w = evaluator.u_values->JxW(q);
            for (unsigned int a = 0; a < evaluator.m_dofs.size(); ++a)
              {
                const auto row = normal_row.find(evaluator.m_dofs[a]);
                if (row == normal_row.end())
                  continue;
                const double psi_a = evaluator.psi(a, q);
                for (unsigned int j = 0; j < n_dofs; ++j)
                  cell_row(j) =
                      w * psi_a * evaluator.u_values->shape_value(j, q) * normal[component[j]];
                constraints.distribute_local_to_global(
                    cell_row, evaluator.u_dofs, trace_rows[row->second]);
                for (unsigned int b = 0; b < evaluator.m_dofs.size(); ++b)
                  {
                    const auto column = normal_row.find(evaluator.m_dofs[b]);
                    if (column != normal_row.end())
                      gram_m(row->second, column->second) += h * w * psi_a * evaluator.psi(b, q);
                  }
              }
          }
      }
    return contact_mesh_size;
  }

  template <int dim>
  FullMatrix<double>
  InfSupTest<dim>::multiplier_prolongation(
      const View &view, const std::map<types::global_dof_index, unsigned int> &normal_row)
  {
    // constrained multipliers (hanging nodes, coarser multiplier mesh) are
    // combinations of free ones, μ = P μ_free
    const AffineConstraints<double> &hanging_constraints = view.hanging_constraints;
    const unsigned int               n_rows              = normal_row.size();
    std::vector<unsigned int>        free_index(n_rows, numbers::invalid_unsigned_int);
    unsigned int                     n_free = 0;
    for (const auto &[dof, row] : normal_row)
      if (!hanging_constraints.is_constrained(dof))
        free_index[row] = n_free++;
    FullMatrix<double> prolongation(n_rows, n_free);
    for (const auto &[dof, row] : normal_row)
      if (free_index[row] != numbers::invalid_unsigned_int)
        prolongation(row, free_index[row]) = 1.;
      else
        for (const auto &[column, weight] : *hanging_constraints.get_constraint_entries(dof))
          prolongation(row, free_index[normal_row.at(column)]) += weight;
    return prolongation;
  }

  template <int dim>
  void
  InfSupTest<dim>::run(const unsigned int                            n_meshes,
                       const std::string                            &directory,
                       const std::function<View(unsigned int mesh)> &mesh) const
  {
    std::filesystem::create_directories(directory);
    const std::string filename = directory + "/inf_sup.csv";
    std::ofstream     table(filename);
    table << "mesh,contact_mesh_size_mm,displacement_dofs,normal_multiplier_dofs,beta\n";
    pcout << "Inf-sup test of the pair " << fe_pair
          << " (normal multiplier in the norm sum_F h_F |mu|^2_L2(F), displacement in H1)\n"
          << "  mesh   h (mm)   displacement DoFs   multiplier DoFs   beta_h\n";
    for (unsigned int k = 1; k <= n_meshes; ++k)
      {
        const InfSupRecord r = compute(mesh(k));
        table << k << ',' << std::setprecision(10) << r.contact_mesh_size << ','
              << r.displacement_dofs << ',' << r.normal_multiplier_dofs << ',' << r.beta << '\n';
        pcout << std::setw(6) << k << std::setw(9) << std::setprecision(4) << r.contact_mesh_size
              << std::setw(20) << r.displacement_dofs << std::setw(18) << r.normal_multiplier_dofs
              << "   " << std::scientific << std::setprecision(4) << r.beta << std::defaultfloat
              << std::endl;
      }
    pcout << "Written to " << filename << "\n";
  }

  template <int dim>
  void
  InfSupTest<dim>::check(const View &view, const unsigned int cycle, TimerOutput &timer)
  {
    if (!checked())
      {
        if (check_asked && cycle == 0)
          pcout << "NOTE: `Contact/Check inf-sup` runs on one MPI rank; not checked on "
                << Utilities::MPI::n_mpi_processes(communicator)
                << " (`--inf-sup N` checks a pair on one rank).\n";
        return;
      }
    TimerOutput::Scope scope(timer, "inf-sup check");
    const InfSupRecord record  = compute(view);
    const double       largest = betas.empty() ? 0. : *std::max_element(betas.begin(), betas.end());
    betas.push_back(record.beta);
    pcout << "Inf-sup check: beta_h = " << record.beta << " (" << record.normal_multiplier_dofs
          << " normal multipliers, contact faces up to " << record.contact_mesh_size << " mm)\n";
    // the stable pairs' beta_h grows towards its limit on coarse meshes and
    // then levels off; an unstable pair's falls (Q1/P0: by 40 % per halving
    // of h) or is zero (a multiplier space richer than the trace: doc/fe_pairs.md)
    if (record.beta < 1e-6)
      pcout << "WARNING: the pair " << fe_pair
            << " is not inf-sup stable on this mesh: beta_h = " << record.beta
            << " (some multipliers act on no displacement; the Newton matrix is singular "
               "where contact is active). A stable pair: doc/fe_pairs.md.\n";
    else if (record.beta < 0.8 * largest)
      pcout << "WARNING: beta_h of the pair " << fe_pair << " fell under refinement, from "
            << largest << " to " << record.beta
            << ": the pair is not inf-sup stable, and its multipliers may oscillate from "
               "node to node on finer meshes. A stable pair: doc/fe_pairs.md.\n";
  }

  template class InfSupTest<2>;
  template class InfSupTest<3>;
} // namespace StabilizedLagrangian
