#include <deal.II/base/geometry_info.h>
#include <deal.II/base/mpi.h>

#include <deal.II/distributed/p4est_wrappers.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

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
    constexpr char magic[] = "stabilized_lagrangian checkpoint 4";
    /** What every version's marker begins with: a file of another version is named as such. */
    constexpr char magic_family[] = "stabilized_lagrangian checkpoint";

    /** The file of @p rank in a checkpoint directory. */
    std::string
    rank_file_name(const unsigned int rank)
    {
      return "rank-" + std::to_string(rank) + ".bin";
    }

    /**
     * FNV-1a (64 bits) of @p bytes: the last 8 bytes of a rank file, so that a
     * changed byte or a cut is found before any of its fields is used.
     */
    std::uint64_t
    checksum(const std::string_view bytes)
    {
      std::uint64_t hash = 14695981039346656037ull;
      for (const unsigned char byte : bytes)
        hash = (hash ^ byte) * 1099511628211ull;
      return hash;
    }

    [[noreturn]] void
    throw_damaged(const std::string &path, const std::string &what)
    {
      throw InputError("the checkpoint file " + path + " is damaged: " + what +
                       ". Start the run again without --resume, or resume from an intact copy "
                       "of the checkpoint.");
    }

    /** Whether @p text is 1 to @p longest decimal digits. */
    bool
    is_number(const std::string &text, const std::size_t longest)
    {
      return !text.empty() && text.size() <= longest &&
             text.find_first_not_of("0123456789") == std::string::npos;
    }

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
      /** The bytes written, followed by their checksum. */
      std::string
      str() const
      {
        std::string   bytes = out.str();
        std::uint64_t sum   = checksum(bytes);
        bytes.append(reinterpret_cast<const char *>(&sum), sizeof(sum));
        return bytes;
      }

    private:
      std::ostringstream out;
    };

    /**
     * The reader of Writer's format, for untrusted bytes: every count is
     * checked against the bytes left before anything is allocated, every
     * string against its longest valid length; a read past the end means a
     * truncated file.
     */
    class Reader
    {
    public:
      Reader(std::string data, std::string path)
          : data(std::move(data))
          , path(std::move(path))
          , end(this->data.size())
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
      get(std::vector<T> &values, const std::string &what)
      {
        static_assert(std::is_trivially_copyable_v<T>);
        values.resize(count(what, sizeof(T)));
        take(values.data(), values.size() * sizeof(T));
      }
      /** A string of at most @p longest characters. */
      void
      get(std::string &text, const std::size_t longest, const std::string &what)
      {
        const std::uint64_t size = count(what, 1);
        if (size > longest)
          damaged(what + " is " + std::to_string(size) + " characters long, at most " +
                  std::to_string(longest) + " are valid");
        text.resize(size);
        take(text.data(), size);
      }
      /** A count of items of at least @p item_bytes bytes each: no more than the bytes left hold.
       */
      std::uint64_t
      count(const std::string &what, const std::size_t item_bytes)
      {
        std::uint64_t n = 0;
        get(n);
        if (n > (end - position) / std::max<std::size_t>(item_bytes, 1))
          damaged("the count of " + what + " is " + std::to_string(n) + ", more than the " +
                  std::to_string(end - position) + " bytes left can hold");
        return n;
      }
      /** Check the file's last 8 bytes against the checksum of the others, all that is read. */
      void
      check_sum()
      {
        std::uint64_t stored = 0;
        if (data.size() < position + sizeof(stored))
          truncated();
        std::memcpy(&stored, data.data() + data.size() - sizeof(stored), sizeof(stored));
        end = data.size() - sizeof(stored);
        if (stored != checksum(std::string_view(data).substr(0, end)))
          damaged("its checksum does not match its content (a byte was changed, or the file was "
                  "cut or extended)");
      }
      bool
      at_end() const
      {
        return position == end;
      }
      [[noreturn]] void
      damaged(const std::string &what) const
      {
        throw_damaged(path, what);
      }
      const std::string &
      file() const
      {
        return path;
      }

    private:
      void
      take(void *destination, const std::size_t size)
      {
        if (size > end - position)
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
      std::size_t       end;
      std::size_t       position = 0;
    };

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

    bool
    all_finite(const std::vector<double> &values)
    {
      return std::all_of(
          values.begin(), values.end(), [](const double x) { return std::isfinite(x); });
    }

    /** Whether the entries of the point or tensor @p t are finite (and not beyond 1e150). */
    template <typename T>
    bool
    finite_tensor(const T &t)
    {
      return std::isfinite(t.norm_square());
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
      if (!is_number(coarse, 9) || !is_number(level, 2) ||
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
     * Everything a rank's checkpoint file holds, read and checked for what
     * needs no mesh: counts, lengths, cell ids, flags, finite values.
     */
    template <int dim> struct SavedState
    {
      std::uint64_t                               n_u = 0, n_multipliers = 0;
      std::vector<std::vector<CellId>>            refinements;
      unsigned int                                cycle = 0;
      double                                      time  = 0.;
      LoadStepController::State                   controller;
      WorkCounters                                work, path_start_work;
      double                                      last_normal_force = 0.;
      std::vector<double>                         owned;
      double                                      last_step_size = 0.;
      std::vector<double>                         segments;
      std::vector<ContactPointState<dim>>         states;
      std::vector<double>                         nodal_states;
      std::vector<Point<dim>>                     active_set;
      std::vector<double>                         history;
      StatisticsWriter::State                     statistics;
      unsigned long                               cycles_bytes = 0;
      std::vector<std::pair<double, std::string>> pvd_records;
      std::vector<double>                         slips;
    };

    /** The cells refined at each refinement of the run, as the checkpoint lists them. */
    template <int dim>
    std::vector<std::vector<CellId>>
    read_refinements(Reader &in)
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

    /** A .pvd record as write_vtu_with_pvtu_record() names it: solution_<step>.pvtu. */
    bool
    is_solution_record(const std::string &name)
    {
      const std::string stem = "solution_", extension = ".pvtu";
      return name.size() > stem.size() + extension.size() && name.rfind(stem, 0) == 0 &&
             name.compare(name.size() - extension.size(), extension.size(), extension) == 0 &&
             is_number(name.substr(stem.size(), name.size() - stem.size() - extension.size()), 9);
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

    /** The accumulated slip: whole entries, keys and steps in their integer ranges. */
    template <int dim>
    bool
    valid_slips(const std::vector<double> &slips)
    {
      const unsigned int entry = 3 * dim + 3;
      if (slips.size() % entry != 0 || !all_finite(slips))
        return false;
      for (std::size_t i = 0; i < slips.size(); i += entry)
        {
          for (unsigned int d = 0; d < dim; ++d)
            if (std::abs(slips[i + d]) >= 9e18) // (within std::int64_t)
              return false;
          if (slips[i + dim] < 0. || slips[i + dim] > std::numeric_limits<unsigned int>::max())
            return false;
        }
      return true;
    }

    /** Read the file of one rank whole and check what needs no mesh. */
    template <int dim>
    SavedState<dim>
    read_saved_state(Reader &in, const unsigned int rank, const unsigned int n_ranks)
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
      SavedState<dim> saved;
      in.get(saved.n_u);
      in.get(saved.n_multipliers);
      saved.refinements = read_refinements<dim>(in);
      in.get(saved.cycle);
      in.get(saved.time);
      in.get(saved.controller);
      in.get(saved.work);
      in.get(saved.path_start_work);
      in.get(saved.last_normal_force);
      in.get(saved.owned, "solution values");
      in.get(saved.last_step_size);
      in.get(saved.segments, "segment values");
      in.get(saved.states, "contact points");
      in.get(saved.nodal_states, "nodal states");
      in.get(saved.active_set, "active set points");
      in.get(saved.history, "material history values");
      in.get(saved.statistics);
      in.get(saved.cycles_bytes);
      // (a record takes at least its time and its name's length)
      saved.pvd_records.resize(in.count(".pvd records", 2 * sizeof(std::uint64_t)));
      for (auto &[t, record] : saved.pvd_records)
        {
          in.get(t);
          in.get(record, 64, "a .pvd record");
          if (!std::isfinite(t) || !is_solution_record(record))
            in.damaged("a .pvd record is not a time and a file solution_<step>.pvtu");
        }
      in.get(saved.slips, "accumulated slip values");
      std::string trailer;
      in.get(trailer, sizeof(magic), "the end marker");
      if (trailer != magic || !in.at_end())
        in.damaged("its end marker is missing");

      const double step_size   = saved.controller.step_size;
      const auto   finite_work = [](const WorkCounters &w) {
        return std::isfinite(w.amg_setup_seconds + w.schur_seconds + w.krylov_seconds +
                             w.schur_solve_seconds);
      };
      if (!std::isfinite(saved.time) || saved.time < 0. || !std::isfinite(step_size) ||
          step_size <= 0. || !std::isfinite(saved.last_step_size) || saved.last_step_size < 0. ||
          !std::isfinite(saved.last_normal_force) || !finite_work(saved.work) ||
          !finite_work(saved.path_start_work))
        in.damaged("its load stepping state (time, step sizes, force, work) is not finite and "
                   "positive");
      if (!all_finite(saved.owned) || !all_finite(saved.segments) ||
          !all_finite(saved.nodal_states) || !all_finite(saved.history))
        in.damaged("its solution, segments, nodal states or material history hold values that "
                   "are not finite");
      if (!valid_states(saved.states) ||
          !std::all_of(saved.active_set.begin(), saved.active_set.end(), [](const auto &p) {
            return finite_tensor(p);
          }))
        in.damaged("its contact points' states hold invalid values");
      if (!valid_slips<dim>(saved.slips))
        in.damaged("its accumulated slip is not a list of whole, finite entries");
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
        if (found == lines.end() || !is_number(found->second, 18))
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
    out.put(static_cast<std::uint64_t>(refinement_history.size()));
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
    SafeFiles::write_atomically(next + "/" + rank_file_name(rank), bytes);

    const auto sizes = Utilities::MPI::gather(mpi_communicator, bytes.size(), 0);
    if (rank == 0)
      {
        SafeFiles::write_atomically(next + "/parameters.prm", parameters_used);
        std::ostringstream manifest;
        manifest << "ranks " << n_ranks << "\nstep " << controller.step << "\ntime " << time
                 << "\ncycle " << cycle << "\n";
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
    MPI_Barrier(mpi_communicator);
    pcout << "  checkpoint written (step " << controller.step << ", t = " << time << ")\n";
  }

  template <int dim>
  void
  ContactProblem<dim>::replay_refinements()
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);
    for (unsigned int r = 0; r < refinement_history.size(); ++r)
      {
        check_on_every_rank(mpi_communicator, [&] {
          for (const auto &id : refinement_history[r])
            {
              const auto cell = find_cell<dim>(triangulation, id);
              if (!cell || !(*cell)->is_active() || !(*cell)->is_locally_owned())
                throw_damaged(find_checkpoint(run_directory) + "/" + rank_file_name(rank),
                              "refinement " + std::to_string(r + 1) + " names the cell " +
                                  id.to_string() +
                                  ", which is not an active cell of this rank on the mesh "
                                  "refined as the checkpoint says before");
              (*cell)->set_refine_flag();
            }
        });
        triangulation.execute_coarsening_and_refinement();
        setup_after_refinement();
      }
  }

  template <int dim>
  unsigned int
  ContactProblem<dim>::restore_checkpoint()
  {
    const unsigned int rank      = Utilities::MPI::this_mpi_process(mpi_communicator);
    const unsigned int n_ranks   = Utilities::MPI::n_mpi_processes(mpi_communicator);
    const std::string  directory = find_checkpoint(run_directory);
    std::string        path;
    SavedState<dim>    saved;
    check_on_every_rank(mpi_communicator, [&] {
      path = rank_file(directory, rank, n_ranks);
      check_resume_parameters(directory, parameters_used);
      Reader in(read_whole(path), path);
      saved = read_saved_state<dim>(in, rank, n_ranks);
      // one refinement before each adaptive refinement cycle after the first
      if (saved.cycle > adaptive_refinement.cycles || saved.refinements.size() != saved.cycle)
        in.damaged("it was taken in refinement cycle " + std::to_string(saved.cycle) + " after " +
                   std::to_string(saved.refinements.size()) + " refinements; the scene has " +
                   std::to_string(adaptive_refinement.cycles) + " cycles");
    });

    // the mesh: the same refinements, cell by cell
    refinement_history = saved.refinements;
    replay_refinements();

    // the state, once it is known to fit the rebuilt mesh
    check_on_every_rank(mpi_communicator, [&] {
      if (saved.n_u != n_u || saved.n_multipliers != n_multipliers)
        throw InputError("the checkpoint in " + directory + " has " + std::to_string(saved.n_u) +
                         " + " + std::to_string(saved.n_multipliers) + " DoFs, the rebuilt mesh " +
                         std::to_string(n_u) + " + " + std::to_string(n_multipliers) +
                         ": the scene's mesh changed.");
      const auto fits =
          [&](const std::size_t size, const std::size_t expected, const std::string &what) {
            if (size != expected)
              throw_damaged(path,
                            "it has " + std::to_string(size) + " " + what + ", the rebuilt mesh " +
                                std::to_string(expected));
          };
      fits(saved.owned.size(), 2 * locally_owned.n_elements(), "solution values");
      try
        {
          restore_segments(saved.segments);
        }
      catch (const InputError &e)
        {
          throw_damaged(path, e.what());
        }
      fits(saved.states.size(), contact_states.size(), "contact points");
      fits(saved.nodal_states.size(), 2 * nodal.owned_nodes.size(), "nodal state values");
      fits(saved.history.size(),
           material_history.committed_data().size(),
           "material history values");
      const bool rigid_partner = chosen.master_boundaries.empty();
      for (const auto &state : saved.states)
        if (state.zone > contact_zones.size() || (rigid_partner && state.pairing.master_face >= 0))
          throw_damaged(path,
                        "a contact point names a contact zone or master face the scene "
                        "does not have");
    });

    cycle             = saved.cycle;
    time              = saved.time;
    controller        = saved.controller;
    work              = saved.work;
    path_start_work   = saved.path_start_work;
    last_normal_force = saved.last_normal_force;
    unsigned int k    = 0;
    for (const auto index : locally_owned)
      solution(index) = saved.owned[k++];
    for (const auto index : locally_owned)
      last_increment(index) = saved.owned[k++];
    solution.compress(VectorOperation::insert);
    last_increment.compress(VectorOperation::insert);
    last_step_size = saved.last_step_size;
    update_ghosts();
    step_start     = ghosted_solution;
    contact_states = saved.states;
    restore_nodal_states(saved.nodal_states);
    active_set = saved.active_set;
    material_history.restore(saved.history);
    pvd_records = saved.pvd_records;
    accumulated_slip.clear();
    const unsigned int entry = 3 * dim + 3;
    for (std::size_t i = 0; i < saved.slips.size(); i += entry)
      {
        const double                 *values = saved.slips.data() + i;
        std::array<std::int64_t, dim> key;
        for (unsigned int d = 0; d < dim; ++d)
          key[d] = static_cast<std::int64_t>(values[d]);
        AccumulatedSlip &slip = accumulated_slip[key];
        slip.step             = static_cast<unsigned int>(values[dim]);
        for (unsigned int d = 0; d < dim; ++d)
          {
            slip.before[d] = values[dim + 1 + d];
            slip.total[d]  = values[2 * dim + 1 + d];
          }
        slip.path_before = values[3 * dim + 1];
        slip.path        = values[3 * dim + 2];
      }

    check_on_every_rank(mpi_communicator, [&] {
      try
        {
          continue_outputs(saved.cycles_bytes, saved.statistics);
        }
      catch (const std::exception &e)
        {
          throw InputError("--resume: the output files in " + run_directory +
                           " do not match the checkpoint in " + directory + ": " + e.what());
        }
    });
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
    output_directory = cycle_directory(cycle);
    statistics.resume(output_directory, dim, root, statistics_supports(), statistics_state);
    write_pvd();
    output_directory = base;
  }

  template <int dim>
  void
  ContactProblem<dim>::restore_segments(const std::vector<double> &segments)
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
        first += face_quadrature(face).size();
      }
    if (k != segments.size())
      throw InputError("it holds segments for more contact faces than the rebuilt mesh has");
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
