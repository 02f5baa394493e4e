#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <type_traits>

namespace StabilizedLagrangian
{
  // Checkpoint and restart (`Output/Checkpoint interval`, `--resume`).
  //
  // The directory `checkpoint` in the output directory holds one binary file
  // per rank (`rank-N.bin`), the parameters of the run and a manifest with the
  // size of every file, written last. A new checkpoint is written into
  // `checkpoint.new` and then renamed over the old one (the old one kept as
  // `checkpoint.old` until the rename is done), so a run killed at any moment
  // leaves the previous or the new checkpoint whole. The mesh is rebuilt as
  // the run built it: the scene's mesh, then the cells each rank flagged at
  // every adaptive refinement, by their CellId; on the same number of ranks
  // p4est then partitions it as before, so the DoF numbering, the contact
  // points and the quadrature history are those of the checkpoint.

  namespace
  {
    constexpr char magic[] = "stabilized_lagrangian checkpoint 3";

    /** Binary writer of trivially copyable values and vectors of them. */
    class Writer
    {
    public:
      template <typename T>
      void
      put(const T &value)
      {
        static_assert(std::is_trivially_copyable_v<T>);
        out.write(reinterpret_cast<const char *>(&value), sizeof(T));
      }
      template <typename T>
      void
      put(const std::vector<T> &values)
      {
        static_assert(std::is_trivially_copyable_v<T>);
        put(static_cast<std::uint64_t>(values.size()));
        out.write(reinterpret_cast<const char *>(values.data()), values.size() * sizeof(T));
      }
      void
      put(const std::string &text)
      {
        put(std::vector<char>(text.begin(), text.end()));
      }
      std::string
      str() const
      {
        return out.str();
      }

    private:
      std::ostringstream out;
    };

    /** The reader of Writer's format; a read past the end means a truncated file. */
    class Reader
    {
    public:
      Reader(std::string data, std::string path)
          : data(std::move(data))
          , path(std::move(path))
      {
      }
      template <typename T>
      void
      get(T &value)
      {
        static_assert(std::is_trivially_copyable_v<T>);
        take(&value, sizeof(T));
      }
      template <typename T>
      void
      get(std::vector<T> &values)
      {
        std::uint64_t size = 0;
        get(size);
        if (size > (data.size() - position) / std::max<std::size_t>(sizeof(T), 1))
          truncated();
        values.resize(size);
        take(values.data(), size * sizeof(T));
      }
      void
      get(std::string &text)
      {
        std::vector<char> characters;
        get(characters);
        text.assign(characters.begin(), characters.end());
      }
      bool
      at_end() const
      {
        return position == data.size();
      }

    private:
      void
      take(void *destination, const std::size_t size)
      {
        if (size > data.size() - position)
          truncated();
        // (an empty vector's data() may be null, which memcpy may not be given)
        if (size > 0)
          std::memcpy(destination, data.data() + position, size);
        position += size;
      }
      [[noreturn]] void
      truncated() const
      {
        throw InputError("the checkpoint file " + path +
                         " is truncated or damaged: it ends before its data does.");
      }
      const std::string data;
      const std::string path;
      std::size_t       position = 0;
    };

    std::string
    read_whole(const std::string &path)
    {
      std::ifstream file(path, std::ios::binary);
      if (!file)
        throw InputError("cannot read the checkpoint file " + path + ".");
      std::ostringstream content;
      content << file.rdbuf();
      return content.str();
    }

    /** "Section/Entry" → value of every entry of a parameter file printed in PRM format. */
    std::map<std::string, std::string>
    entries(const std::string &prm_text)
    {
      std::map<std::string, std::string> result;
      std::vector<std::string>           sections;
      std::istringstream                 lines(prm_text);
      for (std::string line; std::getline(lines, line);)
        {
          line             = line.substr(0, line.find('#'));
          const auto first = line.find_first_not_of(" \t");
          if (first == std::string::npos)
            continue;
          line = line.substr(first, line.find_last_not_of(" \t") + 1 - first);
          if (line.rfind("subsection ", 0) == 0)
            sections.push_back(line.substr(11));
          else if (line == "end" && !sections.empty())
            sections.pop_back();
          else if (line.rfind("set ", 0) == 0 && line.find('=') != std::string::npos)
            {
              std::string path;
              for (const auto &section : sections)
                path += section + "/";
              std::string name  = line.substr(4, line.find('=') - 4);
              name              = name.substr(0, name.find_last_not_of(" \t") + 1);
              std::string value = line.substr(line.find('=') + 1);
              value = value.substr(std::min(value.size(), value.find_first_not_of(" \t")));
              result[path + name] = value;
            }
        }
      return result;
    }

    /** The entries a resume may change: the end of the load path and what is written. */
    bool
    may_change_on_resume(const std::string &entry)
    {
      return entry == "Load stepping/End time" || entry == "Load stepping/Wall time limit" ||
             entry == "Linear solver/Threads per rank" ||
             (entry.rfind("Output/", 0) == 0 && entry != "Output/Output directory");
    }
  } // namespace

  template <int dim>
  void
  ContactProblem<dim>::write_checkpoint() const
  {
    static_assert(std::is_trivially_copyable_v<ContactPointState<dim>>);
    const unsigned int rank    = Utilities::MPI::this_mpi_process(mpi_communicator);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
    // the checkpoint belongs to the output directory of the run, not of a cycle
    const std::string &base = run_directory;
    const std::string  next = base + "/checkpoint.new";
    if (rank == 0)
      {
        std::filesystem::remove_all(next);
        std::filesystem::create_directories(next);
      }
    MPI_Barrier(mpi_communicator);

    Writer out;
    out.put(std::string(magic));
    out.put(dim);
    out.put(n_ranks);
    out.put(rank);
    out.put(static_cast<std::uint64_t>(n_u));
    out.put(static_cast<std::uint64_t>(n_multipliers));
    out.put(static_cast<std::uint32_t>(refinement_history.size()));
    for (const auto &flagged : refinement_history)
      {
        out.put(static_cast<std::uint64_t>(flagged.size()));
        for (const auto &id : flagged)
          out.put(id.to_string());
      }
    out.put(cycle);
    out.put(time);
    out.put(controller);
    out.put(work);
    out.put(path_start_work);
    out.put(last_normal_force);
    std::vector<double> owned;
    for (const auto index : locally_owned)
      owned.push_back(solution(index));
    // the predictor's slope (`Predictor = extrapolation`)
    for (const auto index : locally_owned)
      owned.push_back(last_increment(index));
    out.put(owned);
    out.put(last_step_size);
    // the contact faces' segments (their number of points sets the states' layout)
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
    out.put(segments);
    out.put(contact_states);
    out.put(owned_nodal_states());
    out.put(active_set);
    out.put(material_history.committed_data());
    out.put(statistics.state());
    unsigned long cycles_bytes = 0;
    if (rank == 0 && std::filesystem::exists(base + "/refinement_cycles.csv"))
      cycles_bytes = std::filesystem::file_size(base + "/refinement_cycles.csv");
    out.put(cycles_bytes);
    out.put(static_cast<std::uint64_t>(pvd_records.size()));
    for (const auto &[t, file] : pvd_records)
      {
        out.put(t);
        out.put(file);
      }
    // the accumulated slip of the nodes of Γc: key, step, then the sums
    std::vector<double> slips;
    for (const auto &[key, slip] : accumulated_slip)
      {
        slips.insert(slips.end(), key.begin(), key.end());
        slips.push_back(slip.step);
        for (const Tensor<1, dim> *sum : {&slip.before, &slip.total})
          for (unsigned int d = 0; d < dim; ++d)
            slips.push_back((*sum)[d]);
        slips.push_back(slip.path_before);
        slips.push_back(slip.path);
      }
    out.put(slips);
    out.put(std::string(magic));
    const std::string bytes = out.str();
    SafeFiles::write_atomically(next + "/rank-" + std::to_string(rank) + ".bin", bytes);

    const auto sizes = Utilities::MPI::gather(mpi_communicator, bytes.size(), 0);
    if (rank == 0)
      {
        SafeFiles::write_atomically(next + "/parameters.prm", parameters_used);
        std::ostringstream manifest;
        manifest << "ranks " << n_ranks << "\nstep " << controller.step << "\ntime " << time
                 << "\ncycle " << cycle << "\n";
        for (unsigned int r = 0; r < n_ranks; ++r)
          manifest << "rank-" << r << ".bin " << sizes[r] << "\n";
        // the manifest last: a directory without one is incomplete
        SafeFiles::write_atomically(next + "/manifest", manifest.str());
        const std::string current = base + "/checkpoint", old = base + "/checkpoint.old";
        std::filesystem::remove_all(old);
        if (std::filesystem::exists(current))
          std::filesystem::rename(current, old);
        std::filesystem::rename(next, current);
        std::filesystem::remove_all(old);
      }
    MPI_Barrier(mpi_communicator);
    pcout << "  checkpoint written (step " << controller.step << ", t = " << time << ")\n";
  }

  namespace
  {
    /** The checkpoint directory of @p base, or the previous one when a kill came between the
     * renames. */
    std::string
    find_checkpoint(const std::string &base)
    {
      for (const std::string &candidate : {base + "/checkpoint", base + "/checkpoint.old"})
        if (std::filesystem::exists(candidate + "/manifest"))
          return candidate;
      throw InputError("--resume: no checkpoint in " + base +
                       " (a checkpoint is written every `Output/Checkpoint interval` load "
                       "steps; the interval is 0 unless the parameter file sets it).");
    }

    /**
     * The file of @p rank in the checkpoint @p directory, checked against its
     * manifest: the number of ranks and the size of every rank's file.
     */
    std::string
    rank_file(const std::string &directory, const unsigned int rank, const unsigned int n_ranks)
    {
      std::istringstream manifest(read_whole(directory + "/manifest"));
      std::string        key;
      unsigned int       saved_ranks = 0;
      manifest >> key >> saved_ranks;
      if (key != "ranks" || saved_ranks == 0)
        throw InputError("the checkpoint manifest " + directory + "/manifest is damaged.");
      if (saved_ranks != n_ranks)
        throw InputError("the checkpoint in " + directory + " was written by " +
                         std::to_string(saved_ranks) + " MPI rank(s); resume it with mpirun -np " +
                         std::to_string(saved_ranks) + " (this run has " + std::to_string(n_ranks) +
                         ").");
      std::map<std::string, unsigned long> sizes;
      for (std::string name, value; manifest >> name >> value;)
        if (name.rfind("rank-", 0) == 0)
          sizes[name] = std::stoul(value);
      const std::string file = "rank-" + std::to_string(rank) + ".bin";
      const std::string path = directory + "/" + file;
      if (!std::filesystem::exists(path) || std::filesystem::file_size(path) != sizes[file])
        throw InputError("the checkpoint file " + path + " is truncated or damaged: " +
                         (std::filesystem::exists(path)
                              ? std::to_string(std::filesystem::file_size(path)) + " bytes"
                              : std::string("missing")) +
                         ", the manifest says " + std::to_string(sizes[file]) + " bytes.");
      return path;
    }

    /** The parameters of a resume: only the end time and the output may change. */
    void
    check_resume_parameters(const std::string &directory, const std::string &parameters_used)
    {
      const auto saved   = entries(read_whole(directory + "/parameters.prm"));
      const auto current = entries(parameters_used);
      for (const auto &[entry, value] : current)
        {
          const auto        found  = saved.find(entry);
          const std::string before = found == saved.end() ? "(not declared)" : found->second;
          if (before != value && !may_change_on_resume(entry))
            throw InputError(
                "--resume: the entry " + entry + " is '" + value +
                "', the checkpoint was written with '" + before +
                "'. A resume may change only Load stepping/End time and Wall time limit, "
                "the Output entries other than the directory and Linear "
                "solver/Threads per rank; run from the start for other changes.");
        }
    }

    /** The cells refined at each refinement of the run, as the checkpoint lists them. */
    std::vector<std::vector<CellId>>
    read_refinements(Reader &in)
    {
      std::uint32_t n_refinements = 0;
      in.get(n_refinements);
      std::vector<std::vector<CellId>> history(n_refinements);
      for (auto &flagged : history)
        {
          std::uint64_t n_cells = 0;
          in.get(n_cells);
          for (std::uint64_t c = 0; c < n_cells; ++c)
            {
              std::string id;
              in.get(id);
              flagged.push_back(CellId(id));
            }
        }
      return history;
    }
  } // namespace

  template <int dim>
  void
  ContactProblem<dim>::replay_refinements()
  {
    for (const auto &flagged : refinement_history)
      {
        for (const auto &id : flagged)
          {
            const auto cell = triangulation.create_cell_iterator(id);
            AssertThrow(cell->is_active() && cell->is_locally_owned(),
                        ExcMessage("the checkpoint's refinements do not fit this mesh"));
            cell->set_refine_flag();
          }
        triangulation.execute_coarsening_and_refinement();
        setup_after_refinement();
      }
  }

  template <int dim>
  unsigned int
  ContactProblem<dim>::restore_checkpoint()
  {
    const unsigned int rank      = Utilities::MPI::this_mpi_process(mpi_communicator);
    const std::string &base      = run_directory;
    const std::string  directory = find_checkpoint(base);
    const std::string  path =
        rank_file(directory, rank, Utilities::MPI::n_mpi_processes(mpi_communicator));
    check_resume_parameters(directory, parameters_used);

    Reader      in(read_whole(path), path);
    std::string header;
    in.get(header);
    int          saved_dim     = 0;
    unsigned int saved_n_ranks = 0, saved_rank = 0;
    in.get(saved_dim);
    in.get(saved_n_ranks);
    in.get(saved_rank);
    if (header != magic && header.rfind("stabilized_lagrangian checkpoint", 0) == 0)
      throw InputError("the checkpoint file " + path + " was written by another version of the " +
                       "program ('" + header + "'; this one reads '" + magic +
                       "'): start the run again without --resume.");
    if (header != magic || saved_dim != dim || saved_rank != rank)
      throw InputError("the checkpoint file " + path + " is not a " + std::to_string(dim) +
                       "D checkpoint of rank " + std::to_string(rank) + ".");
    std::uint64_t saved_n_u = 0, saved_n_multipliers = 0;
    in.get(saved_n_u);
    in.get(saved_n_multipliers);

    // the mesh: the same refinements, cell by cell
    refinement_history = read_refinements(in);
    replay_refinements();
    if (saved_n_u != n_u || saved_n_multipliers != n_multipliers)
      throw InputError("the checkpoint in " + directory + " has " + std::to_string(saved_n_u) +
                       " + " + std::to_string(saved_n_multipliers) + " DoFs, the rebuilt mesh " +
                       std::to_string(n_u) + " + " + std::to_string(n_multipliers) +
                       ": the scene's mesh changed.");

    unsigned int saved_cycle = 0;
    in.get(saved_cycle);
    in.get(time);
    in.get(controller);
    in.get(work);
    in.get(path_start_work);
    in.get(last_normal_force);
    std::vector<double> owned;
    in.get(owned);
    AssertThrow(owned.size() == 2 * locally_owned.n_elements(),
                ExcMessage("the checkpoint's solution does not fit this mesh"));
    unsigned int k = 0;
    for (const auto index : locally_owned)
      solution(index) = owned[k++];
    for (const auto index : locally_owned)
      last_increment(index) = owned[k++];
    solution.compress(VectorOperation::insert);
    last_increment.compress(VectorOperation::insert);
    in.get(last_step_size);
    update_ghosts();
    step_start = ghosted_solution;
    std::vector<double> segments;
    in.get(segments);
    restore_segments(segments);
    std::vector<ContactPointState<dim>> states;
    in.get(states);
    AssertThrow(states.size() == contact_states.size(),
                ExcMessage("the checkpoint's contact points do not fit this mesh"));
    contact_states = states;
    std::vector<double> nodal_states;
    in.get(nodal_states);
    restore_nodal_states(nodal_states);
    in.get(active_set);
    std::vector<double> history;
    in.get(history);
    material_history.restore(history);
    StatisticsWriter::State statistics_state;
    in.get(statistics_state);
    unsigned long cycles_bytes = 0;
    in.get(cycles_bytes);
    std::uint64_t n_records = 0;
    in.get(n_records);
    pvd_records.resize(n_records);
    for (auto &[t, record] : pvd_records)
      {
        in.get(t);
        in.get(record);
      }
    std::vector<double> slips;
    in.get(slips);
    accumulated_slip.clear();
    const unsigned int entry = 3 * dim + 3;
    AssertThrow(slips.size() % entry == 0,
                ExcMessage("the checkpoint's accumulated slip is damaged"));
    for (unsigned int i = 0; i < slips.size(); i += entry)
      {
        std::array<std::int64_t, dim> key;
        for (unsigned int d = 0; d < dim; ++d)
          key[d] = static_cast<std::int64_t>(slips[i + d]);
        AccumulatedSlip &slip = accumulated_slip[key];
        slip.step             = static_cast<unsigned int>(slips[i + dim]);
        for (unsigned int d = 0; d < dim; ++d)
          {
            slip.before[d] = slips[i + dim + 1 + d];
            slip.total[d]  = slips[i + 2 * dim + 1 + d];
          }
        slip.path_before = slips[i + 3 * dim + 1];
        slip.path        = slips[i + 3 * dim + 2];
      }
    std::string trailer;
    in.get(trailer);
    if (trailer != magic || !in.at_end())
      throw InputError("the checkpoint file " + path + " is damaged: its end marker is missing.");

    cycle = saved_cycle;
    continue_outputs(cycles_bytes, statistics_state);
    pcout << "Resuming from " << directory << ": step " << controller.step << ", t = " << time
          << (adaptive_refinement.cycles > 0 ? ", refinement cycle " + std::to_string(cycle)
                                             : std::string())
          << "\n";
    return cycle;
  }

  template <int dim>
  void
  ContactProblem<dim>::continue_outputs(const unsigned long            cycles_bytes,
                                        const StatisticsWriter::State &statistics_state)
  {
    // the output continues where the checkpoint was taken: a killed run may have
    // written rows and files of later steps
    const std::string &base = run_directory;
    const bool         root = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    if (root && cycles_bytes > 0)
      SafeFiles::truncate(base + "/refinement_cycles.csv", cycles_bytes);
    output_parameters.directory = cycle_directory(cycle);
    statistics.resume(
        output_parameters.directory, dim, root, statistics_supports(), statistics_state);
    write_pvd();
    output_parameters.directory = base;
  }

  template <int dim>
  void
  ContactProblem<dim>::restore_segments(const std::vector<double> &segments)
  {
    // the faces of the checkpoint's mesh, in the same order: each one's rule
    std::size_t  k     = 0;
    unsigned int first = 0;
    for (auto &face : contact_faces)
      {
        AssertThrow(k < segments.size(),
                    ExcMessage("the checkpoint's contact faces do not fit this mesh"));
        const auto n = static_cast<unsigned int>(segments[k++]);
        AssertThrow(k + n * dim <= segments.size(),
                    ExcMessage("the checkpoint's contact faces do not fit this mesh"));
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
        first += face_quadrature(face).size();
      }
    contact_states.resize(first);
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                 \
  template void         ContactProblem<dim>::write_checkpoint() const;                      \
  template unsigned int ContactProblem<dim>::restore_checkpoint();                          \
  template void         ContactProblem<dim>::restore_segments(const std::vector<double> &); \
  template void         ContactProblem<dim>::replay_refinements();                          \
  template void         ContactProblem<dim>::continue_outputs(unsigned long,                \
                                                      const StatisticsWriter::State &);

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
