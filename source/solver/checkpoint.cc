#include <deal.II/base/geometry_info.h>
#include <deal.II/base/mpi.h>

#include <deal.II/distributed/p4est_wrappers.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/checkpoint.h>
#include <stabilized_lagrangian/solver/state_archive.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
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
  //
  // A checkpoint is a file a user can damage or replace: it is read as
  // untrusted input. A rank file ends with a checksum of its bytes, checked
  // before any field is used; then every count is checked against the bytes
  // left, every string against its longest valid length, the cell ids are
  // parsed here (deal.II's CellId parser trusts its input) and found by walking
  // down the mesh, and every size against the rebuilt mesh. Whatever does not
  // fit stops the run on every rank with an InputError naming the file.

  namespace
  {
    constexpr char magic[] = "stabilized_lagrangian checkpoint 6";
    /** What every version's marker begins with: a file of another version is named as such. */
    constexpr char magic_family[] = "stabilized_lagrangian checkpoint";

    /** The file of @p rank in a checkpoint directory. */
    std::string
    rank_file_name(const unsigned int rank)
    {
      return "rank-" + std::to_string(rank) + ".bin";
    }

    std::string
    read_whole(const std::string &path)
    {
      if (!std::filesystem::is_regular_file(path))
        throw InputError("the checkpoint file " + path + " is missing or not a file.");
      std::ifstream file(path, std::ios::binary);
      if (!file)
        throw InputError("cannot read the checkpoint file " + path + ".");
      std::ostringstream content;
      content << file.rdbuf();
      return content.str();
    }

    /**
     * Run @p check on this rank; when it throws InputError on any rank, throw
     * the first such rank's message on every rank, so that none waits in a
     * collective call for one that stopped. @p check makes no collective call.
     */
    template <typename Check>
    void
    check_on_every_rank(const MPI_Comm communicator, const Check &check)
    {
      std::string error;
      try
        {
          check();
        }
      catch (const InputError &e)
        {
          error = e.what();
        }
      for (const auto &message : Utilities::MPI::all_gather(communicator, error))
        if (!message.empty())
          throw InputError(message);
    }

    /**
     * The cell id "<coarse cell>_<level>:<child indices>" of a checkpoint,
     * parsed without trusting it: digits where digits belong, the level at
     * most the deepest a p4est mesh of dimension @p dim has (within CellId's
     * fixed capacity), one child index below 2^dim per level. Empty when
     * @p text is no such id.
     */
    template <int dim>
    std::optional<CellId>
    parse_cell_id(const std::string &text)
    {
      const auto underscore = text.find('_');
      const auto colon      = text.find(':');
      if (underscore == std::string::npos || colon == std::string::npos || colon < underscore)
        return {};
      const std::string coarse   = text.substr(0, underscore);
      const std::string level    = text.substr(underscore + 1, colon - underscore - 1);
      const std::string children = text.substr(colon + 1);
      // (9 digits fit every coarse cell index type)
      if (!is_decimal_number(coarse, 9) || !is_decimal_number(level, 2) ||
          std::stoul(level) > dealii::internal::p4est::functions<dim>::max_level ||
          children.size() != std::stoul(level))
        return {};
      std::vector<std::uint8_t> child_indices;
      for (const char c : children)
        {
          if (c < '0' || c - '0' >= static_cast<int>(GeometryInfo<dim>::max_children_per_cell))
            return {};
          child_indices.push_back(c - '0');
        }
      return CellId(std::stoul(coarse), child_indices);
    }

    /** The cell @p id names, found by walking down from its coarse cell; empty if none. */
    template <int dim>
    std::optional<typename Triangulation<dim>::cell_iterator>
    find_cell(const Triangulation<dim> &triangulation, const CellId &id)
    {
      // (on a p4est mesh a CellId's coarse cell is the coarse cell's index)
      if (id.get_coarse_cell_id() >= triangulation.n_cells(0))
        return {};
      typename Triangulation<dim>::cell_iterator cell(&triangulation, 0, id.get_coarse_cell_id());
      for (const auto child : id.get_child_indices())
        {
          if (!cell->has_children() || child >= cell->n_children())
            return {};
          cell = cell->child(child);
        }
      return cell;
    }

    /**
     * A rank's checkpoint file, read and checked for what needs no mesh: the
     * header (the mesh the state lives on: its DoFs, the refinements of the
     * run, the cycle), then the bytes of every entry of the run's state.
     */
    struct SavedState
    {
      std::uint64_t                    n_u = 0, n_multipliers = 0;
      std::vector<std::vector<CellId>> refinements;
      unsigned int                     cycle = 0;
      std::vector<std::string>         entries;
    };

    /** The cells refined at each refinement of the run, as the checkpoint lists them. */
    template <int dim>
    std::vector<std::vector<CellId>>
    read_refinements(StateReader &in)
    {
      // (a refinement takes at least its count of cells, a cell id its length)
      std::vector<std::vector<CellId>> history(in.count("refinements", sizeof(std::uint64_t)));
      for (unsigned int r = 0; r < history.size(); ++r)
        {
          const std::string refinement = "refinement " + std::to_string(r + 1);
          const auto        n_cells    = in.count("cells of " + refinement, sizeof(std::uint64_t));
          for (std::uint64_t c = 0; c < n_cells; ++c)
            {
              std::string text;
              in.get(text, 64, "a cell id of " + refinement);
              const auto id = parse_cell_id<dim>(text);
              if (!id)
                in.damaged(refinement + " names the cell '" + text +
                           "', which is no cell id of a " + std::to_string(dim) + "D mesh");
              history[r].push_back(*id);
            }
        }
      return history;
    }

    /** Read the file of one rank whole and check what needs no mesh. */
    template <int dim>
    SavedState
    read_saved_state(StateReader       &in,
                     const RunState    &state,
                     const unsigned int rank,
                     const unsigned int n_ranks)
    {
      std::string header;
      in.get(header, sizeof(magic) + 16, "the header");
      if (header != magic && header.rfind(magic_family, 0) == 0)
        throw InputError("the checkpoint file " + in.file() +
                         " was written by another version of the program ('" + header +
                         "'; this one reads '" + magic +
                         "'): start the run again without --resume.");
      if (header != magic)
        in.damaged("it does not begin with '" + std::string(magic) + "'");
      in.check_sum();
      int          saved_dim     = 0;
      unsigned int saved_n_ranks = 0, saved_rank = 0;
      in.get(saved_dim);
      in.get(saved_n_ranks);
      in.get(saved_rank);
      if (saved_dim != dim || saved_n_ranks != n_ranks || saved_rank != rank)
        throw InputError("the checkpoint file " + in.file() + " is not a " + std::to_string(dim) +
                         "D checkpoint of rank " + std::to_string(rank) + " of " +
                         std::to_string(n_ranks) + ".");
      SavedState saved;
      in.get(saved.n_u);
      in.get(saved.n_multipliers);
      saved.refinements = read_refinements<dim>(in);
      in.get(saved.cycle);
      saved.entries = state.read_entries(in);
      std::string trailer;
      in.get(trailer, sizeof(magic), "the end marker");
      if (trailer != magic || !in.at_end())
        in.damaged("its end marker is missing");
      return saved;
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
      const std::string                  manifest_path = directory + "/manifest";
      std::istringstream                 manifest(read_whole(manifest_path));
      std::map<std::string, std::string> lines;
      for (std::string key, value; manifest >> key >> value;)
        lines[key] = value;
      const auto number = [&](const std::string &key) {
        const auto found = lines.find(key);
        if (found == lines.end() || !is_decimal_number(found->second, 18))
          throw InputError("the checkpoint manifest " + manifest_path +
                           " is damaged: it has no line '" + key + " <number>'.");
        return std::stoul(found->second);
      };
      const unsigned long saved_ranks = number("ranks");
      if (saved_ranks == 0)
        throw InputError("the checkpoint manifest " + manifest_path +
                         " is damaged: it says 0 ranks wrote the checkpoint.");
      if (saved_ranks != n_ranks)
        throw InputError("the checkpoint in " + directory + " was written by " +
                         std::to_string(saved_ranks) + " MPI rank(s); resume it with mpirun -np " +
                         std::to_string(saved_ranks) + " (this run has " + std::to_string(n_ranks) +
                         ").");
      const std::string   file = rank_file_name(rank);
      const std::string   path = directory + "/" + file;
      const unsigned long size = number(file);
      if (!std::filesystem::is_regular_file(path) || std::filesystem::file_size(path) != size)
        throw InputError("the checkpoint file " + path + " is truncated or damaged: " +
                         (std::filesystem::is_regular_file(path)
                              ? std::to_string(std::filesystem::file_size(path)) + " bytes"
                              : std::string("missing or not a file")) +
                         ", the manifest says " + std::to_string(size) + " bytes.");
      return path;
    }

    /** The parameters of a resume: only the end time and the output may change. */
    void
    check_resume_parameters(const std::string &directory, const std::string &parameters_used)
    {
      const auto saved   = entries(read_whole(directory + "/parameters.prm"));
      const auto current = entries(parameters_used);
      if (saved.empty())
        throw InputError("the checkpoint's parameter file " + directory +
                         "/parameters.prm is damaged: it sets no entry.");
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
  } // namespace

  template <int dim>
  void
  Checkpoint<dim>::write() const
  {
    const unsigned int rank    = Utilities::MPI::this_mpi_process(view.communicator);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(view.communicator);
    // the checkpoint belongs to the output directory of the run, not of a cycle
    const std::string &base = view.run_directory;
    const std::string  next = base + "/checkpoint.new";
    if (rank == 0)
      {
        std::filesystem::remove_all(next);
        std::filesystem::create_directories(next);
      }
    MPI_Barrier(view.communicator);

    StateWriter out;
    out.put(std::string(magic));
    out.put(dim);
    out.put(n_ranks);
    out.put(rank);
    // the mesh the state lives on
    out.put(static_cast<std::uint64_t>(view.n_u));
    out.put(static_cast<std::uint64_t>(view.n_multipliers));
    out.put(static_cast<std::uint64_t>(view.refinement_history.size()));
    for (const auto &flagged : view.refinement_history)
      {
        out.put(static_cast<std::uint64_t>(flagged.size()));
        for (const auto &id : flagged)
          out.put(id.to_string());
      }
    out.put(view.cycle);
    view.state_list.write(out);
    out.put(std::string(magic));
    const std::string bytes = out.sealed();
    SafeFiles::write_atomically(next + "/" + rank_file_name(rank), bytes);

    const auto sizes = Utilities::MPI::gather(view.communicator, bytes.size(), 0);
    if (rank == 0)
      {
        SafeFiles::write_atomically(next + "/parameters.prm", view.parameters_used);
        std::ostringstream manifest;
        manifest << "ranks " << n_ranks << "\nstep " << view.controller.step << "\ntime "
                 << view.time << "\ncycle " << view.cycle << "\n";
        for (unsigned int r = 0; r < n_ranks; ++r)
          manifest << rank_file_name(r) << " " << sizes[r] << "\n";
        // the manifest last: a directory without one is incomplete
        SafeFiles::write_atomically(next + "/manifest", manifest.str());
        const std::string current = base + "/checkpoint", old = base + "/checkpoint.old";
        std::filesystem::remove_all(old);
        if (std::filesystem::exists(current))
          std::filesystem::rename(current, old);
        std::filesystem::rename(next, current);
        std::filesystem::remove_all(old);
      }
    MPI_Barrier(view.communicator);
    view.pcout << "  checkpoint written (step " << view.controller.step << ", t = " << view.time
               << ")\n";
  }

  template <int dim>
  void
  Checkpoint<dim>::replay_refinements()
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(view.communicator);
    for (unsigned int r = 0; r < view.refinement_history.size(); ++r)
      {
        check_on_every_rank(view.communicator, [&] {
          for (const auto &id : view.refinement_history[r])
            {
              const auto cell = find_cell<dim>(view.triangulation, id);
              if (!cell || !(*cell)->is_active() || !(*cell)->is_locally_owned())
                throw_damaged_checkpoint(
                    find_checkpoint(view.run_directory) + "/" + rank_file_name(rank),
                    "refinement " + std::to_string(r + 1) + " names the cell " + id.to_string() +
                        ", which is not an active cell of this rank on the mesh "
                        "refined as the checkpoint says before");
              (*cell)->set_refine_flag();
            }
        });
        view.triangulation.execute_coarsening_and_refinement();
        view.setup_after_refinement();
      }
  }

  template <int dim>
  unsigned int
  Checkpoint<dim>::restore()
  {
    const unsigned int rank      = Utilities::MPI::this_mpi_process(view.communicator);
    const unsigned int n_ranks   = Utilities::MPI::n_mpi_processes(view.communicator);
    const std::string  directory = find_checkpoint(view.run_directory);
    std::string        path;
    SavedState         saved;
    check_on_every_rank(view.communicator, [&] {
      path = rank_file(directory, rank, n_ranks);
      check_resume_parameters(directory, view.parameters_used);
      StateReader in(read_whole(path), path);
      saved = read_saved_state<dim>(in, view.state_list, rank, n_ranks);
      // one refinement before each adaptive refinement cycle after the first
      if (saved.cycle > view.adaptive_refinement.cycles || saved.refinements.size() != saved.cycle)
        in.damaged("it was taken in refinement cycle " + std::to_string(saved.cycle) + " after " +
                   std::to_string(saved.refinements.size()) + " refinements; the scene has " +
                   std::to_string(view.adaptive_refinement.cycles) + " cycles");
    });

    // the mesh: the same refinements, cell by cell
    view.refinement_history = saved.refinements;
    replay_refinements();

    // the state, once it is known to fit the rebuilt mesh
    std::vector<std::function<void()>> put_back;
    check_on_every_rank(view.communicator, [&] {
      if (saved.n_u != view.n_u || saved.n_multipliers != view.n_multipliers)
        throw InputError("the checkpoint in " + directory + " has " + std::to_string(saved.n_u) +
                         " + " + std::to_string(saved.n_multipliers) + " DoFs, the rebuilt mesh " +
                         std::to_string(view.n_u) + " + " + std::to_string(view.n_multipliers) +
                         ": the scene's mesh changed.");
      put_back = view.state_list.load(saved.entries, path);
    });
    view.cycle = saved.cycle;
    for (const auto &put : put_back)
      if (put)
        put();
    // (the same time on every rank: all refuse together)
    if (view.time > view.end_time * (1. + 1e-12))
      {
        std::ostringstream message;
        message << "--resume: Load stepping/End time = " << view.end_time
                << " is before the time of the checkpoint in " << directory << ", t = " << view.time
                << ": nothing is left to solve. Set End time after it to continue the load path, "
                   "or run without --resume to start again.";
        throw InputError(message.str());
      }
    view.pcout << "Resuming from " << directory << ": step " << view.controller.step
               << ", t = " << view.time
               << (view.adaptive_refinement.cycles > 0
                       ? ", refinement cycle " + std::to_string(view.cycle)
                       : std::string())
               << "\n";
    return view.cycle;
  }

  template <int dim>
  void
  Checkpoint<dim>::continue_outputs(const unsigned long            cycles_bytes,
                                    const StatisticsWriter::State &statistics_state)
  {
    // the output continues where the checkpoint was taken: a killed run may have
    // written rows and files of later steps
    const std::string &base = view.run_directory;
    const bool         root = Utilities::MPI::this_mpi_process(view.communicator) == 0;
    check_on_every_rank(view.communicator, [&] {
      try
        {
          if (root && cycles_bytes > 0)
            SafeFiles::truncate(base + "/refinement_cycles.csv", cycles_bytes);
          view.output_directory = view.cycle_directory(view.cycle);
          view.statistics.resume(
              view.output_directory, dim, root, view.statistics_supports(), statistics_state);
          view.solution_output.write_pvd(view.output_directory);
        }
      catch (const std::exception &e)
        {
          view.output_directory = base;
          throw InputError("--resume: the output files in " + base +
                           " do not match the checkpoint in " + find_checkpoint(base) + ": " +
                           e.what());
        }
    });
    view.output_directory = base;
  }

  template <int dim>
  unsigned long
  Checkpoint<dim>::cycles_log_bytes() const
  {
    const std::string log = view.run_directory + "/refinement_cycles.csv";
    if (Utilities::MPI::this_mpi_process(view.communicator) == 0 && std::filesystem::exists(log))
      return std::filesystem::file_size(log);
    return 0;
  }

  // Explicit instantiation of the members defined in this file.
#define SL_INSTANTIATE(dim)                                                                        \
  template void         Checkpoint<dim>::write() const;                                            \
  template unsigned int Checkpoint<dim>::restore();                                                \
  template void         Checkpoint<dim>::replay_refinements();                                     \
  template void Checkpoint<dim>::continue_outputs(unsigned long, const StatisticsWriter::State &); \
  template unsigned long Checkpoint<dim>::cycles_log_bytes() const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
