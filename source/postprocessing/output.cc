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

#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

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
     * DataOut that can say which of its fields holds a value a VTU file
     * cannot carry: the patches store single precision, so a finite double
     * beyond 3.4e38 (an absurd stiffness times a strain) becomes inf, and a
     * NaN stays one. Nothing of the kind may reach a file (DESIGN.md §8).
     */
    template <int dim> class CheckedDataOut : public DataOut<dim>
    {
    public:
      /**
       * @brief The name of the first field with a value that is not finite in
       * the patches of any rank, or an empty string (collective).
       */
      std::string
      non_finite_field(const MPI_Comm communicator) const
      {
        const std::vector<std::string> names = this->get_dataset_names();
        std::string                    field;
        for (const auto &patch : this->get_patches())
          for (unsigned int row = 0; row < patch.data.n_rows() && field.empty(); ++row)
            for (unsigned int point = 0; point < patch.data.n_cols(); ++point)
              if (!std::isfinite(patch.data(row, point)))
                {
                  field = row < names.size() ? names[row] : "the vertex coordinates";
                  break;
                }
        for (const auto &name : Utilities::MPI::all_gather(communicator, field))
          if (!name.empty())
            return name;
        return "";
      }
    };

    /**
     * Cauchy stress tensor and von Mises stress, averaged over the quadrature
     * points of each cell where the history variables live (plane strain:
     * the out-of-plane stress enters the von Mises stress).
     */
    template <int dim> class CellStressPostprocessor : public DataPostprocessor<dim>
    {
    public:
      /** @p hoop: an axisymmetric model, whose σ_θθ is a field of its own */
      CellStressPostprocessor(const std::vector<Tensor<2, 3>> &cell_stress, const bool hoop)
          : cell_stress(cell_stress)
          , hoop(hoop)
      {
      }

      void
      evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &inputs,
                            std::vector<Vector<double>>                &computed) const override
      {
        const Tensor<2, 3> &sigma =
            cell_stress[inputs.template get_cell<dim>()->active_cell_index()];
        const Tensor<2, 3> deviator  = sigma - trace(sigma) / 3. * unit_symmetric_tensor<3>();
        const double       von_mises = std::sqrt(1.5 * scalar_product(deviator, deviator));
        for (auto &values : computed)
          {
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                values(i * dim + j) = sigma[i][j];
            values(dim * dim) = von_mises;
            if (hoop)
              values(dim * dim + 1) = sigma[2][2];
          }
      }

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names(dim * dim, "stress_MPa");
        names.push_back("von_mises_stress_MPa");
        if (hoop)
          names.push_back("hoop_stress_MPa");
        return names;
      }

      std::vector<DataComponentInterpretation::DataComponentInterpretation>
      get_data_component_interpretation() const override
      {
        std::vector<DataComponentInterpretation::DataComponentInterpretation> kinds(
            dim * dim, DataComponentInterpretation::component_is_part_of_tensor);
        kinds.push_back(DataComponentInterpretation::component_is_scalar);
        if (hoop)
          kinds.push_back(DataComponentInterpretation::component_is_scalar);
        return kinds;
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_default;
      }

    private:
      const std::vector<Tensor<2, 3>> &cell_stress;
      const bool                       hoop;
    };

    /** The boundary faces of the locally owned cells that a predicate keeps (the contact faces). */
    template <int dim> class BoundaryFacesOut : public DataOutFaces<dim>
    {
    public:
      using FaceDescriptor = typename DataOutFaces<dim>::FaceDescriptor;
      using Keep =
          std::function<bool(const typename Triangulation<dim>::cell_iterator &, unsigned int)>;

      explicit BoundaryFacesOut(Keep keep)
          : DataOutFaces<dim>(true)
          , keep(std::move(keep))
      {
      }

      FaceDescriptor
      first_face() override
      {
        return first_kept(DataOutFaces<dim>::first_face());
      }

      FaceDescriptor
      next_face(const FaceDescriptor &face) override
      {
        return first_kept(DataOutFaces<dim>::next_face(face));
      }

    private:
      /** @p face or the first face after it that keep() accepts */
      FaceDescriptor
      first_kept(FaceDescriptor face)
      {
        while (face.first.state() == IteratorState::valid && !keep(face.first, face.second))
          face = DataOutFaces<dim>::next_face(face);
        return face;
      }

      const Keep keep;
    };

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
  } // namespace

  template <int dim>
  std::vector<std::string>
  ContactProblem<dim>::history_field_names() const
  {
    std::vector<std::string> names;
    for (const auto &body : materials)
      for (const auto &name : body.model->history_field_names())
        if (std::find(names.begin(), names.end(), name) == names.end())
          names.push_back(name);
    return names;
  }

  template <int dim>
  void
  ContactProblem<dim>::compute_cell_averages(const TrilinosWrappers::MPI::Vector &u,
                                             std::vector<Tensor<2, 3>>           &cell_stress,
                                             std::vector<Vector<float>> &cell_history_fields) const
  {
    const unsigned int n_cells = triangulation.n_active_cells();
    compute_volume_fields(u);
    cell_stress.assign(n_cells, Tensor<2, 3>());
    const std::vector<std::string> names = history_field_names();
    cell_history_fields.assign(names.size(), Vector<float>(n_cells));
    FEValues<dim> fe_values(
        *fe_u, cell_quadrature, update_gradients | update_values | update_quadrature_points);
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<2, dim>>      gradients(cell_quadrature.size());
    std::vector<Tensor<1, dim>>      values(cell_quadrature.size()); // axisymmetric: u_r/r
    const double                     weight = 1. / cell_quadrature.size();
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(u, gradients);
          fe_values[displacement].get_function_values(u, values);
          const unsigned int               index       = cell->active_cell_index();
          const Materials::Interface<dim> &material    = material_of(cell);
          const std::vector<std::string>   field_names = material.history_field_names();
          for (unsigned int q = 0; q < cell_quadrature.size(); ++q)
            {
              // the committed history is that of this converged state
              const auto   history = material_history.committed(index, q);
              const double hoop =
                  hoop_strain(fe_values.quadrature_point(q), values[q], gradients[q]);
              const auto response = committed_response(
                  cell, q, cell_quadrature.point(q), gradients[q], nullptr, hoop);
              cell_stress[index] +=
                  weight * Materials::cauchy_stress(
                               gradients[q], response, material.is_finite_strain(), hoop);
              const std::vector<double> fields = material.history_fields(history);
              for (unsigned int f = 0; f < fields.size(); ++f)
                cell_history_fields[std::find(names.begin(), names.end(), field_names[f]) -
                                    names.begin()][index] += weight * fields[f];
            }
        }
  }

  /**
   * One contact output field: a Q1 field of the VTU, averaged at the vertices
   * of Γc, and columns of the profile, at every node of Γc; both evaluated
   * from the converged iterate at a point (doc/formulation.md).
   */
  template <int dim> struct ContactProblem<dim>::ContactField
  {
    /** What a field is evaluated from at a point. */
    using Sample = ContactSample<dim>;

    std::string  name;       ///< of the VTU field
    std::string  column;     ///< the profile's columns are column[_x|_y|_z][_unit]
    std::string  unit;       ///< empty for a number without unit
    unsigned int components; ///< 1 (a scalar) or dim (a vector)
    /** append the field's components at a point to the values */
    std::function<void(const Sample &, std::vector<double> &)> evaluate;
  };

  template <int dim>
  std::vector<typename ContactProblem<dim>::ContactField>
  ContactProblem<dim>::contact_fields()
  {
    using Sample = typename ContactField::Sample;
    using Values = std::vector<double>;
    // a tangential vector in the pairing's basis, in Cartesian components
    const auto append = [](const Sample &p, const Tensor<1, dim - 1> &t, Values &values) {
      const Tensor<1, dim> v = p.state.pairing.from_tangential_components(t);
      for (unsigned int d = 0; d < dim; ++d)
        values.push_back(v[d]);
    };
    // the cumulative slip is the solver's, committed before the output (CumulativeSlip)
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

  template <int dim>
  void
  ContactProblem<dim>::sample_contact_fields(const std::vector<ContactField>       &fields,
                                             const std::vector<ContactSample<dim>> &samples,
                                             const DoFHandler<dim>                 &field_dofs,
                                             TrilinosWrappers::MPI::Vector         &vertex_values,
                                             std::vector<double>                   &profile) const
  {
    IndexSet field_relevant;
    DoFTools::extract_locally_relevant_dofs(field_dofs, field_relevant);
    TrilinosWrappers::MPI::Vector sums;
    sums.reinit(field_dofs.locally_owned_dofs(), field_relevant, mpi_communicator, true);
    TrilinosWrappers::MPI::Vector counts(sums);
    const unsigned int            n_components = field_dofs.get_fe().n_components();

    // every node goes into the profile, in reference coordinates; the
    // vertices also into the vertex fields
    for (const auto &sample : samples)
      {
        const typename DoFHandler<dim>::active_cell_iterator field_cell(
            &triangulation, sample.cell->level(), sample.cell->index(), &field_dofs);
        const auto          vertex_face = field_cell->face(sample.face_no);
        const double        tolerance   = 1e-10 * vertex_face->diameter();
        const Point<dim>   &X           = sample.reference_position;
        std::vector<double> values;
        for (const auto &field : fields)
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
    if (fields.back().name == "contact_status")
      status_mask.set(n_components - 1, true);
    const IndexSet status_dofs = DoFTools::extract_dofs(field_dofs, status_mask);
    vertex_values.reinit(field_dofs.locally_owned_dofs(), mpi_communicator);
    for (const auto index : field_dofs.locally_owned_dofs())
      vertex_values(index) = counts(index) > 0.              ? sums(index) / counts(index)
                             : status_dofs.is_element(index) ? -1.
                                                             : 0.;
    vertex_values.compress(VectorOperation::insert);
  }

  template <int dim>
  void
  ContactProblem<dim>::output_results(const unsigned int                     step,
                                      const double                           t,
                                      const std::vector<ContactSample<dim>> &samples)
  {
    const std::vector<ContactField> fields       = contact_fields();
    unsigned int                    n_components = 0;
    for (const auto &field : fields)
      n_components += field.components;
    // the contact fields at the vertices of Γc, on a Q1 (P1) field (zero elsewhere)
    const FESystem<dim> fe_fields = simplex_mesh()
                                        ? FESystem<dim>(FE_SimplexP<dim>(1), n_components)
                                        : FESystem<dim>(FE_Q<dim>(1), n_components);
    DoFHandler<dim>     field_dofs(triangulation);
    field_dofs.distribute_dofs(fe_fields);
    TrilinosWrappers::MPI::Vector vertex_values;
    std::vector<double>           profile;
    sample_contact_fields(fields, samples, field_dofs, vertex_values, profile);
    if (output_parameters.write_vtu)
      write_solution(step, t, fields, field_dofs, vertex_values);
    if (output_parameters.write_profiles && step > 0)
      write_profile(step, fields, profile);
  }

  namespace
  {
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
  } // namespace

  template <int dim>
  void
  ContactProblem<dim>::write_solution(const unsigned int                   step,
                                      const double                         t,
                                      const std::vector<ContactField>     &fields,
                                      const DoFHandler<dim>               &field_dofs,
                                      const TrilinosWrappers::MPI::Vector &vertex_values)
  {
    const std::string                  &directory = output_directory;
    const TrilinosWrappers::MPI::Vector u         = ghosted_displacement();
    IndexSet                            field_relevant;
    DoFTools::extract_locally_relevant_dofs(field_dofs, field_relevant);
    TrilinosWrappers::MPI::Vector vertex_ghosted(
        field_dofs.locally_owned_dofs(), field_relevant, mpi_communicator);
    vertex_ghosted = vertex_values;

    CheckedDataOut<dim>                                                         data_out;
    const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector_kind(
        dim, DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(
        dof_handler_u, u, std::vector<std::string>(dim, "displacement_mm"), vector_kind);
    std::vector<Tensor<2, 3>>  cell_stress;
    std::vector<Vector<float>> cell_history_fields;
    compute_cell_averages(u, cell_stress, cell_history_fields);
    const CellStressPostprocessor<dim> stress(cell_stress, axisymmetric);
    data_out.add_data_vector(dof_handler_u, u, stress);
    const std::vector<std::string> history_names = history_field_names();
    for (unsigned int f = 0; f < history_names.size(); ++f)
      data_out.add_data_vector(cell_history_fields[f], history_names[f]);

    // the contact fields, named with their units
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
    data_out.add_data_vector(field_dofs, vertex_ghosted, names, kinds);

    Vector<float> subdomain(triangulation.n_active_cells());
    for (auto &value : subdomain)
      value = triangulation.locally_owned_subdomain();
    data_out.add_data_vector(subdomain, "subdomain");
    // η_K of the residual error estimate (√(N mm)); zero before the first step
    if (error_indicators.size() != triangulation.n_active_cells())
      error_indicators.reinit(triangulation.n_active_cells());
    data_out.add_data_vector(error_indicators, "error_indicator_sqrtNmm");
    data_out.build_patches(fe_pair->displacement_degree());
    const std::string non_finite = data_out.non_finite_field(mpi_communicator);
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
            directory + "/", "solution", step, mpi_communicator, 5, 0);
      }
    catch (const std::exception &)
      {
        throw solution_write_error(
            directory, step, Utilities::MPI::this_mpi_process(mpi_communicator) == 0);
      }
    // the contact surface itself: the fields at its nodes, not smeared into cells
    BoundaryFacesOut<dim> surface_out(
        [this](const typename Triangulation<dim>::cell_iterator &cell, const unsigned int f) {
          return is_contact_face(cell, f);
        });
    surface_out.add_data_vector(
        dof_handler_u, u, std::vector<std::string>(dim, "displacement_mm"), vector_kind);
    surface_out.add_data_vector(field_dofs, vertex_ghosted, names, kinds);
    surface_out.build_patches(fe_pair->displacement_degree());
    // a piece per rank that holds contact faces (an empty piece has no Points
    // element, which VTK's readers report as an error), listed by rank 0
    const unsigned int local_faces = contact_faces.size();
    const unsigned int rank        = Utilities::MPI::this_mpi_process(mpi_communicator);
    const std::string  stem        = "contact_surface_" + Utilities::int_to_string(step, 5);
    const auto         faces       = Utilities::MPI::all_gather(mpi_communicator, local_faces);
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
    if (Utilities::MPI::logical_or(!written, mpi_communicator))
      throw solution_write_error(directory, step, rank == 0, "contact_surface");
    // the .pvd lists a step only once every rank's piece is complete
    MPI_Barrier(mpi_communicator);
    pvd_records.emplace_back(t, record);
    write_pvd();
    write_obstacle(step, t);
  }

  template <int dim>
  void
  ContactProblem<dim>::write_obstacle(const unsigned int step, const double t) const
  {
    if (!partner->is_rigid())
      return;
    // the body's bounding box, over every rank's cells
    Point<dim> low, high;
    for (unsigned int d = 0; d < dim; ++d)
      {
        low[d]  = std::numeric_limits<double>::max();
        high[d] = -std::numeric_limits<double>::max();
      }
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < dim; ++d)
            {
              low[d]  = std::min(low[d], cell->vertex(v)[d]);
              high[d] = std::max(high[d], cell->vertex(v)[d]);
            }
    for (unsigned int d = 0; d < dim; ++d)
      {
        low[d]  = Utilities::MPI::min(low[d], mpi_communicator);
        high[d] = Utilities::MPI::max(high[d], mpi_communicator);
      }
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    Triangulation<dim - 1, dim> surface;
    obstacle->make_surface_mesh(surface, BoundingBox<dim>(std::make_pair(low, high)));
    const Contact::RigidMotion<dim> motion = obstacle_motion->at(t);
    GridTools::transform([&motion](const Point<dim> &X) { return motion.apply(X); }, surface);
    DataOut<dim - 1, dim> data_out;
    data_out.attach_triangulation(surface);
    data_out.build_patches();
    std::ostringstream vtu;
    data_out.write_vtu(vtu);
    const std::string name = "obstacle_" + Utilities::int_to_string(step, 5) + ".vtu";
    SafeFiles::write_atomically(output_directory + "/" + name, vtu.str());
    // the same steps as solution.pvd
    std::ostringstream pvd;
    DataOutBase::write_pvd_record(pvd, records_of(pvd_records, "obstacle", ".vtu"));
    SafeFiles::write_atomically(output_directory + "/obstacle.pvd", pvd.str());
  }

  template <int dim>
  void
  ContactProblem<dim>::write_profile(const unsigned int               step,
                                     const std::vector<ContactField> &fields,
                                     const std::vector<double>       &profile) const
  {
    const auto gathered = Utilities::MPI::gather(mpi_communicator, profile, 0);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    std::vector<std::string> columns;
    for (unsigned int d = 0; d < dim; ++d)
      columns.push_back(std::string(1, "xyz"[d]) + "_mm");
    for (const auto &field : fields)
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
    name << output_directory << "/profile-" << std::setw(5) << std::setfill('0') << step << ".csv";
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

  namespace
  {
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
  } // namespace

  template <int dim>
  void
  ContactProblem<dim>::prepare_output_directory() const
  {
    // rank 0 checks and clears; every rank learns its verdict
    std::string error;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      try
        {
          namespace fs        = std::filesystem;
          const fs::path path = output_directory;
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
          error = "Output/Output directory = '" + output_directory +
                  "': the directory cannot be created, cleared or written (" + e.what() + ").";
        }
    error = Utilities::MPI::broadcast(mpi_communicator, error, 0);
    if (!error.empty())
      throw InputError(error);
  }

  template <int dim>
  void
  ContactProblem<dim>::write_pvd() const
  {
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    std::ostringstream pvd;
    DataOutBase::write_pvd_record(pvd, pvd_records);
    SafeFiles::write_atomically(output_directory + "/solution.pvd", pvd.str());
    std::ostringstream surface;
    DataOutBase::write_pvd_record(surface, records_of(pvd_records, "contact_surface", ".pvtu"));
    SafeFiles::write_atomically(output_directory + "/contact_surface.pvd", surface.str());
  }

  // the class itself is instantiated once, in contact_problem.cc
  template void
  ContactProblem<2>::write_obstacle(unsigned int, double) const;
  template void
  ContactProblem<3>::write_obstacle(unsigned int, double) const;
  template void
  ContactProblem<2>::output_results(unsigned int, double, const std::vector<ContactSample<2>> &);
  template void
  ContactProblem<3>::output_results(unsigned int, double, const std::vector<ContactSample<3>> &);
  template void
  ContactProblem<2>::prepare_output_directory() const;
  template void
  ContactProblem<3>::prepare_output_directory() const;
  template void
  ContactProblem<2>::write_pvd() const;
  template void
  ContactProblem<3>::write_pvd() const;
} // namespace StabilizedLagrangian
