#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_out_faces.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/data_out_dof_data.h>

#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/plugins.h>
#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/postprocessing/solution_output.h>
#include <stabilized_lagrangian/postprocessing/vtu_data_out.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace
  {
    /**
     * The records of @p records (solution_<step>.pvtu) renamed to the file
     * @p stem_<step>@p extension of the same step.
     */
    std::vector<std::pair<double, std::string>>
    records_of(const std::vector<std::pair<double, std::string>> &records,
               const std::string                                 &stem,
               const std::string                                 &extension)
    {
      std::vector<std::pair<double, std::string>> renamed;
      for (const auto &[time, record] : records)
        {
          const auto digits = record.find_last_of('_');
          renamed.emplace_back(
              time, stem + record.substr(digits, record.rfind('.') - digits) + extension);
        }
      return renamed;
    }

    /**
     * The contact output fields, in the order of the VTU's and the profile's;
     * the cumulative slip is the solver's, committed before the output
     * (CumulativeSlip).
     */
    template <int dim>
    std::vector<ContactOutputField<dim>>
    make_contact_fields()
    {
      using Sample = ContactSample<dim>;
      using Values = std::vector<double>;
      // a tangential vector in the pairing's basis, in Cartesian components
      const auto append = [](const Sample &p, const Tensor<1, dim - 1> &t, Values &values) {
        const Tensor<1, dim> v = p.state.pairing.from_tangential_components(t);
        for (unsigned int d = 0; d < dim; ++d)
          values.push_back(v[d]);
      };
      return {
          {"contact_pressure",
           "contact_pressure",
           "MPa",
           1,
           [](const Sample &p, Values &values) { values.push_back(p.response.normal_traction()); }},
          {"tangential_traction",
           "tangential_traction",
           "MPa",
           dim,
           [append](const Sample &p, Values &values) {
             append(p, p.response.tangential_traction(), values);
           }},
          {"gap", "gap", "mm", 1, [](const Sample &p, Values &values) { values.push_back(p.gap); }},
          {"slip_increment",
           "slip_increment",
           "mm",
           dim,
           [append](const Sample &p, Values &values) {
             append(p, p.state.pairing.tangential_components(p.kinematics.step_increment), values);
           }},
          {"cumulative_slip",
           "cumulative_slip",
           "mm",
           dim,
           [](const Sample &p, Values &values) {
             for (unsigned int d = 0; d < dim; ++d)
               values.push_back(p.cumulative_slip[d]);
           }},
          {"slip_path",
           "slip_path",
           "mm",
           1,
           [](const Sample &p, Values &values) { values.push_back(p.slip_path); }},
          {"contact_status", "status", "", 1, [](const Sample &p, Values &values) {
             values.push_back(static_cast<double>(p.response.status()));
           }}};
    }

    /**
     * Remove what a failed write of the solution of @p step left in
     * @p directory (on rank 0) and say why it failed.
     */
    std::runtime_error
    solution_write_error(const std::string &directory,
                         const unsigned int step,
                         const bool         root,
                         const std::string &name = "solution")
    {
      const int error = errno;
      // no half-written piece of this step is left behind
      const std::string stem = name + "_" + Utilities::int_to_string(step, 5);
      if (root)
        for (const auto &entry : std::filesystem::directory_iterator(directory))
          if (entry.path().filename().string().rfind(stem, 0) == 0)
            std::filesystem::remove(entry.path());
      return std::runtime_error(
          "cannot write the solution of step " + std::to_string(step) + " (" + stem +
          ".pvtu) into " + directory + ": " + SafeFiles::free_space_note(directory) +
          (error != 0 ? std::string(" (the system says: ") + std::strerror(error) + ")"
                      : std::string()));
    }

    /** Whether @p name is a file this program writes into an output directory. */
    bool
    is_run_output(const std::string &name)
    {
      const auto starts = [&](const char *prefix) { return name.rfind(prefix, 0) == 0; };
      const auto ends   = [&](const char *suffix) {
        const std::string s(suffix);
        return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
      };
      return (starts("solution") && (ends(".vtu") || ends(".pvtu") || ends(".pvd"))) ||
             (starts("obstacle") && (ends(".vtu") || ends(".pvd"))) ||
             (starts("contact_surface") && (ends(".vtu") || ends(".pvtu") || ends(".pvd"))) ||
             (starts("profile-") && ends(".csv")) || starts("cycle-") || starts("checkpoint") ||
             name == "statistics.csv" || name == "iterations.csv" || name == "run_summary.csv" ||
             name == "refinement_cycles.csv" || name == "parameters.prm" || ends(".tmp");
    }

    /**
     * Add the contact @p fields to @p out (a DataOut or a DataOutFaces), named
     * with their units: @p values, their vertex values on @p field_dofs.
     */
    template <int dim, typename Out>
    void
    add_contact_fields(Out                                        &out,
                       const std::vector<ContactOutputField<dim>> &fields,
                       const DoFHandler<dim>                      &field_dofs,
                       const TrilinosWrappers::MPI::Vector        &values)
    {
      std::vector<std::string>                                              names;
      std::vector<DataComponentInterpretation::DataComponentInterpretation> kinds;
      for (const auto &field : fields)
        for (unsigned int c = 0; c < field.components; ++c)
          {
            names.push_back(field.name + (field.unit.empty() ? "" : "_" + field.unit));
            kinds.push_back(field.components == 1
                                ? DataComponentInterpretation::component_is_scalar
                                : DataComponentInterpretation::component_is_part_of_vector);
          }
      out.add_data_vector(field_dofs, values, names, kinds);
    }
  } // namespace

  template <int dim>
  SolutionOutput<dim>::SolutionOutput(const MPI_Comm            communicator,
                                      const Parameters::Output &parameters)
      : communicator(communicator)
      , write_vtu(parameters.write_vtu)
      , write_profiles(parameters.write_profiles)
      , contact_fields(make_contact_fields<dim>())
  {
  }

  template <int dim>
  void
  SolutionOutput<dim>::write(const unsigned int step,
                             const double       t,
                             const View        &view,
                             const std::string &directory)
  {
    unsigned int n_components = 0;
    for (const auto &field : contact_fields)
      n_components += field.components;
    // the contact fields at the vertices of Γc, on a Q1 (P1) field (zero elsewhere)
    const FESystem<dim> fe_fields = view.simplex ? FESystem<dim>(FE_SimplexP<dim>(1), n_components)
                                                 : FESystem<dim>(FE_Q<dim>(1), n_components);
    DoFHandler<dim>     field_dofs(view.triangulation);
    field_dofs.distribute_dofs(fe_fields);
    TrilinosWrappers::MPI::Vector vertex_values;
    std::vector<double>           profile;
    sample_contact_fields(view, field_dofs, vertex_values, profile);
    if (write_vtu)
      write_solution(step, t, view, directory, field_dofs, vertex_values);
    if (write_profiles && step > 0)
      write_profile(step, directory, profile);
  }

  template <int dim>
  void
  SolutionOutput<dim>::sample_contact_fields(const View                    &view,
                                             const DoFHandler<dim>         &field_dofs,
                                             TrilinosWrappers::MPI::Vector &vertex_values,
                                             std::vector<double>           &profile) const
  {
    IndexSet field_relevant;
    DoFTools::extract_locally_relevant_dofs(field_dofs, field_relevant);
    TrilinosWrappers::MPI::Vector sums;
    sums.reinit(field_dofs.locally_owned_dofs(), field_relevant, communicator, true);
    TrilinosWrappers::MPI::Vector counts(sums);
    const unsigned int            n_components = field_dofs.get_fe().n_components();

    // every node goes into the profile, in reference coordinates; the
    // vertices also into the vertex fields
    for (const auto &sample : view.contact_samples)
      {
        const typename DoFHandler<dim>::active_cell_iterator field_cell(
            &view.triangulation, sample.cell->level(), sample.cell->index(), &field_dofs);
        const auto          vertex_face = field_cell->face(sample.face_no);
        const double        tolerance   = 1e-10 * vertex_face->diameter();
        const Point<dim>   &X           = sample.reference_position;
        std::vector<double> values;
        for (const auto &field : contact_fields)
          field.evaluate(sample, values);
        for (unsigned int d = 0; d < dim; ++d)
          profile.push_back(X[d]);
        profile.insert(profile.end(), values.begin(), values.end());
        for (const unsigned int v : vertex_face->vertex_indices())
          if (vertex_face->vertex(v).distance(X) < tolerance)
            for (unsigned int c = 0; c < n_components; ++c)
              {
                const auto index = vertex_face->vertex_dof_index(v, c);
                sums(index) += values[c];
                counts(index) += 1.;
              }
      }
    sums.compress(VectorOperation::add);
    counts.compress(VectorOperation::add);
    // off Γc every field is 0, the status −1 (0 is "open")
    ComponentMask status_mask(n_components, false);
    if (contact_fields.back().name == "contact_status")
      status_mask.set(n_components - 1, true);
    const IndexSet status_dofs = DoFTools::extract_dofs(field_dofs, status_mask);
    vertex_values.reinit(field_dofs.locally_owned_dofs(), communicator);
    for (const auto index : field_dofs.locally_owned_dofs())
      vertex_values(index) = counts(index) > 0.              ? sums(index) / counts(index)
                             : status_dofs.is_element(index) ? -1.
                                                             : 0.;
    vertex_values.compress(VectorOperation::insert);
  }

  template <int dim>
  void
  SolutionOutput<dim>::write_solution(const unsigned int                   step,
                                      const double                         t,
                                      const View                          &view,
                                      const std::string                   &directory,
                                      const DoFHandler<dim>               &field_dofs,
                                      const TrilinosWrappers::MPI::Vector &vertex_values)
  {
    const TrilinosWrappers::MPI::Vector &u = view.displacement;
    IndexSet                             field_relevant;
    DoFTools::extract_locally_relevant_dofs(field_dofs, field_relevant);
    TrilinosWrappers::MPI::Vector vertex_ghosted(
        field_dofs.locally_owned_dofs(), field_relevant, communicator);
    vertex_ghosted = vertex_values;

    internal::CheckedDataOut<dim>                                               data_out;
    const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector_kind(
        dim, DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(
        view.displacement_dofs, u, std::vector<std::string>(dim, "displacement_mm"), vector_kind);
    const CellAverages                          &averages = view.cell_averages;
    const internal::CellStressPostprocessor<dim> stress(averages.stress, view.axisymmetric);
    data_out.add_data_vector(view.displacement_dofs, u, stress);
    for (unsigned int f = 0; f < averages.history_names.size(); ++f)
      data_out.add_data_vector(averages.history_fields[f], averages.history_names[f]);

    add_contact_fields(data_out, contact_fields, field_dofs, vertex_ghosted);

    Vector<float> subdomain(view.triangulation.n_active_cells());
    for (auto &value : subdomain)
      value = view.triangulation.locally_owned_subdomain();
    data_out.add_data_vector(subdomain, "subdomain");
    // η_K of the residual error estimate (√(N mm)); zero before the first step's
    const unsigned int  n_cells   = view.triangulation.n_active_cells();
    const bool          estimated = view.error_indicators.size() == n_cells;
    const Vector<float> no_estimate(estimated ? 0 : n_cells);
    data_out.add_data_vector(estimated ? view.error_indicators : no_estimate,
                             "error_indicator_sqrtNmm");
    data_out.build_patches(view.displacement_degree);
    const std::string non_finite = data_out.non_finite_field(communicator);
    if (!non_finite.empty())
      throw std::runtime_error(
          "the solution of step " + std::to_string(step) + " (t = " + std::to_string(t) +
          ") is not written: its field " + non_finite +
          " holds a value that is not finite or beyond the single precision of a VTU file "
          "(3.4e38). Check the magnitudes of the input (Young's moduli, loads, r_n and r_t): "
          "their products must stay within that range. The earlier steps are in " +
          directory + ".");
    std::string record;
    try
      {
        record = data_out.write_vtu_with_pvtu_record(
            directory + "/", "solution", step, communicator, 5, 0);
      }
    catch (const std::exception &)
      {
        throw solution_write_error(
            directory, step, Utilities::MPI::this_mpi_process(communicator) == 0);
      }
    write_contact_surface(step, view, directory, field_dofs, vertex_ghosted);
    // the .pvd lists a step only once every rank's piece is complete
    MPI_Barrier(communicator);
    pvd_records.emplace_back(t, record);
    write_pvd(directory);
    write_obstacle(step, t, view, directory);
  }

  template <int dim>
  void
  SolutionOutput<dim>::write_contact_surface(
      const unsigned int                   step,
      const View                          &view,
      const std::string                   &directory,
      const DoFHandler<dim>               &field_dofs,
      const TrilinosWrappers::MPI::Vector &vertex_values) const
  {
    // the contact surface itself: the fields at its nodes, not smeared into cells
    internal::BoundaryFacesOut<dim> surface_out(view.is_contact_face);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector_kind(
        dim, DataComponentInterpretation::component_is_part_of_vector);
    surface_out.add_data_vector(view.displacement_dofs,
                                view.displacement,
                                std::vector<std::string>(dim, "displacement_mm"),
                                vector_kind);
    add_contact_fields(surface_out, contact_fields, field_dofs, vertex_values);
    surface_out.build_patches(view.displacement_degree);
    // a piece per rank that holds contact faces (an empty piece has no Points
    // element, which VTK's readers report as an error), listed by rank 0
    const unsigned int local_faces = view.n_contact_faces;
    const unsigned int rank        = Utilities::MPI::this_mpi_process(communicator);
    const std::string  stem        = "contact_surface_" + Utilities::int_to_string(step, 5);
    const auto         faces       = Utilities::MPI::all_gather(communicator, local_faces);
    bool               written     = true;
    if (local_faces > 0)
      {
        std::ofstream piece(directory + "/" + stem + "." + std::to_string(rank) + ".vtu");
        surface_out.write_vtu(piece);
        written = static_cast<bool>(piece);
      }
    if (rank == 0 && written)
      {
        std::vector<std::string> pieces;
        for (unsigned int r = 0; r < faces.size(); ++r)
          if (faces[r] > 0)
            pieces.push_back(stem + "." + std::to_string(r) + ".vtu");
        std::ofstream record_file(directory + "/" + stem + ".pvtu");
        surface_out.write_pvtu_record(record_file, pieces);
        written = static_cast<bool>(record_file);
      }
    if (Utilities::MPI::logical_or(!written, communicator))
      throw solution_write_error(directory, step, rank == 0, "contact_surface");
  }

  template <int dim>
  void
  SolutionOutput<dim>::write_obstacle(const unsigned int step,
                                      const double       t,
                                      const View        &view,
                                      const std::string &directory) const
  {
    if (!view.rigid_obstacle)
      return;
    // the body's bounding box, over every rank's cells
    Point<dim> low, high;
    for (unsigned int d = 0; d < dim; ++d)
      {
        low[d]  = std::numeric_limits<double>::max();
        high[d] = -std::numeric_limits<double>::max();
      }
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < dim; ++d)
            {
              low[d]  = std::min(low[d], cell->vertex(v)[d]);
              high[d] = std::max(high[d], cell->vertex(v)[d]);
            }
    for (unsigned int d = 0; d < dim; ++d)
      {
        low[d]  = Utilities::MPI::min(low[d], communicator);
        high[d] = Utilities::MPI::max(high[d], communicator);
      }
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    Triangulation<dim - 1, dim> surface;
    view.rigid_obstacle->make_surface_mesh(surface, BoundingBox<dim>(std::make_pair(low, high)));
    const Contact::RigidMotion<dim> motion = view.obstacle_motion.at(t);
    GridTools::transform([&motion](const Point<dim> &X) { return motion.apply(X); }, surface);
    DataOut<dim - 1, dim> data_out;
    data_out.attach_triangulation(surface);
    data_out.build_patches();
    std::ostringstream vtu;
    data_out.write_vtu(vtu);
    const std::string name = "obstacle_" + Utilities::int_to_string(step, 5) + ".vtu";
    SafeFiles::write_atomically(directory + "/" + name, vtu.str());
    // the same steps as solution.pvd
    std::ostringstream pvd;
    DataOutBase::write_pvd_record(pvd, records_of(pvd_records, "obstacle", ".vtu"));
    SafeFiles::write_atomically(directory + "/obstacle.pvd", pvd.str());
  }

  template <int dim>
  void
  SolutionOutput<dim>::write_profile(const unsigned int         step,
                                     const std::string         &directory,
                                     const std::vector<double> &profile) const
  {
    const auto gathered = Utilities::MPI::gather(communicator, profile, 0);
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    std::vector<std::string> columns;
    for (unsigned int d = 0; d < dim; ++d)
      columns.push_back(std::string(1, "xyz"[d]) + "_mm");
    for (const auto &field : contact_fields)
      for (unsigned int c = 0; c < field.components; ++c)
        columns.push_back(field.column + (field.components > 1 ? std::string("_") + "xyz"[c] : "") +
                          (field.unit.empty() ? "" : "_" + field.unit));
    // one row per node: faces sharing a node give it once (coordinates
    // rounded to 1e-9 mm identify it)
    const unsigned int                                 row_size = columns.size();
    std::map<std::vector<double>, std::vector<double>> rows;
    for (const auto &part : gathered)
      for (unsigned int r = 0; r + row_size <= part.size(); r += row_size)
        {
          std::vector<double> key(part.begin() + r, part.begin() + r + dim);
          for (double &x : key)
            x = std::round(x * 1e9) / 1e9;
          rows[key] = std::vector<double>(part.begin() + r, part.begin() + r + row_size);
        }
    std::vector<std::vector<double>> sorted;
    for (auto &entry : rows)
      sorted.push_back(entry.second);
    std::sort(sorted.begin(), sorted.end());
    std::ostringstream name;
    name << directory << "/profile-" << std::setw(5) << std::setfill('0') << step << ".csv";
    std::ostringstream file;
    for (unsigned int c = 0; c < columns.size(); ++c)
      file << (c ? "," : "") << columns[c];
    file << '\n' << std::setprecision(15);
    for (const auto &row : sorted)
      {
        for (unsigned int c = 0; c < row.size(); ++c)
          file << (c ? "," : "") << row[c];
        file << '\n';
      }
    SafeFiles::write_atomically(name.str(), file.str());
  }

  template <int dim>
  void
  SolutionOutput<dim>::prepare_directory(const std::string &directory) const
  {
    // rank 0 checks and clears; every rank learns its verdict
    std::string error;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      try
        {
          namespace fs        = std::filesystem;
          const fs::path path = directory;
          fs::create_directories(path);
          // the files of an earlier run would mix with this one's (a longer
          // run leaves later steps behind): the program owns them and removes them
          for (const auto &entry : fs::directory_iterator(path))
            {
              const std::string name = entry.path().filename().string();
              if (!is_run_output(name))
                continue;
              const bool owned_directory =
                  name.rfind("cycle-", 0) == 0 || name.rfind("checkpoint", 0) == 0;
              if (entry.is_directory() && !owned_directory)
                throw std::runtime_error(entry.path().string() +
                                         " is a directory, where the run writes a file");
              fs::remove_all(entry.path());
            }
          SafeFiles::write_atomically((path / "statistics.csv").string(), "");
          fs::remove(path / "statistics.csv");
        }
      catch (const std::exception &e)
        {
          error = "Output/Output directory = '" + directory +
                  "': the directory cannot be created, cleared or written (" + e.what() + ").";
        }
    error = Utilities::MPI::broadcast(communicator, error, 0);
    if (!error.empty())
      throw InputError(error);
  }

  template <int dim>
  void
  SolutionOutput<dim>::write_pvd(const std::string &directory) const
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    std::ostringstream pvd;
    DataOutBase::write_pvd_record(pvd, pvd_records);
    SafeFiles::write_atomically(directory + "/solution.pvd", pvd.str());
    std::ostringstream surface;
    DataOutBase::write_pvd_record(surface, records_of(pvd_records, "contact_surface", ".pvtu"));
    SafeFiles::write_atomically(directory + "/contact_surface.pvd", surface.str());
  }

  template class SolutionOutput<2>;
  template class SolutionOutput<3>;
} // namespace StabilizedLagrangian
