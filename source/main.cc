#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <default_scene.h>

#include <sched.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <new>
#include <stdexcept>
#include <system_error>
#include <thread>

namespace
{
  using namespace dealii;
  using namespace StabilizedLagrangian;

  const char *usage = R"(Usage: stabilized_lagrangian [--threads N] [--resume] [input.prm]
       stabilized_lagrangian --inf-sup [N] input.prm
       stabilized_lagrangian --print-parameters [2|3]
       stabilized_lagrangian --help

Quasi-static frictional contact with the stabilized Lagrangian mixed
formulation (nested fixed points: geometry, friction threshold, contact
status, Newton). Without an argument the built-in default scene runs:
the elastic patin of the seed paper (prm/patin_elastic.prm).

  input.prm            run the scene described by this parameter file
  --resume             continue from the last checkpoint in the output directory
                       (Output/Checkpoint interval), on the same number of ranks
  --threads N          BLAS/OpenMP threads per MPI rank (default: the entry
                       Linear solver/Threads per rank, 1), at most the
                       processors a rank has and what the address-space limit
                       (ulimit -v) leaves room for; the environment's
                       OPENBLAS_NUM_THREADS and OMP_NUM_THREADS are ignored
  --inf-sup [N]        numerical inf-sup test of the scene's FE pair on its mesh
                       and N - 1 global refinements (default N = 4): beta_h per
                       mesh, printed and written to inf_sup.csv; one MPI rank
  --print-parameters   list every entry with its documentation and default
                       (for dimension 2, or the dimension given)
  --help               this text

Output goes to the directory of the entry Output/Output directory.
)";

  /**
   * @brief The BLAS/OpenMP threads each rank runs for @p requested: at most the
   * processors a rank has (those it may run on, and the node's shared among its
   * ranks), and at most as many as the address space left under its limit
   * (ulimit -v) holds OpenBLAS's per-thread buffers for, since OpenBLAS
   * retries a buffer allocation that fails for ever (`--threads 256` under
   * `ulimit -v 8000000` never ended). The same on every rank; @p note says why
   * when it is fewer. Throws InputError when not even one buffer fits.
   */
  unsigned int
  usable_threads(const unsigned int requested, std::string &note)
  {
    cpu_set_t          allowed;
    const unsigned int hardware = std::max(1u, std::thread::hardware_concurrency());
    const unsigned int affinity =
        sched_getaffinity(0, sizeof(allowed), &allowed) == 0 ? CPU_COUNT(&allowed) : hardware;
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    const unsigned int ranks_on_node = Utilities::MPI::n_mpi_processes(node);
    MPI_Comm_free(&node);
    const unsigned int processors = Utilities::MPI::min(
        std::max(1u, std::min(affinity, hardware / ranks_on_node)), MPI_COMM_WORLD);

    // OpenBLAS's buffer per thread (BUFFER_SIZE of Debian's build: 128 MiB) in
    // at most three quarters of the address space left: the rest is the problem's
    constexpr double mib = 1024. * 1024., blas_buffer = 128. * mib;
    struct rlimit    limit;
    double           threads_fit = 256.;
    double           left        = 0.;
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      {
        Utilities::System::MemoryStats memory;
        Utilities::System::get_memory_stats(memory);
        left        = static_cast<double>(limit.rlim_cur) - 1024. * memory.VmSize;
        threads_fit = std::floor(0.75 * left / blas_buffer);
      }
    const unsigned int by_memory = Utilities::MPI::min(
        static_cast<unsigned int>(std::clamp(threads_fit, 0., 256.)), MPI_COMM_WORLD);
    if (by_memory == 0)
      throw InputError("the address-space limit (ulimit -v) leaves " +
                       std::to_string(static_cast<long>(left / mib)) +
                       " MiB to a rank beyond its libraries, too little for the buffer of one "
                       "BLAS thread (128 MiB) and the problem: raise the limit.");
    const unsigned int usable = std::min({requested, processors, by_memory});
    if (usable < requested)
      note = "Linear solver/Threads per rank = " + std::to_string(requested) + ": " +
             std::to_string(usable) + " BLAS/OpenMP thread(s) per rank are used, " +
             (usable == processors
                  ? "the processors a rank has (" + std::to_string(affinity) + " it may run on, " +
                        std::to_string(hardware) + " on the node for " +
                        std::to_string(ranks_on_node) + " rank(s))"
                  : "as many as the address space left under its limit (ulimit -v), " +
                        std::to_string(static_cast<long>(left / mib)) +
                        " MiB, holds 128 MiB BLAS buffers for with room for the problem") +
             ".\n";
    return usable;
  }

  /** What the program was doing, for a failure's message ("out of memory while ..."). */
  std::string phase = "reading the command line";

  template <int dim>
  int
  run(const std::string &text,
      const bool         is_file,
      const unsigned int inf_sup_meshes,
      const std::string &threads,
      const bool         resume)
  {
    ParameterHandler prm;
    Parameters::declare_all<dim>(prm);
    const auto sections = Parameters::parse<dim>(prm, text, is_file);
    prm.enter_subsection("Linear solver");
    if (!threads.empty())
      prm.set("Threads per rank", threads);
    std::string        note;
    const unsigned int requested = prm.get_integer("Threads per rank");
    const unsigned int usable    = usable_threads(requested, note);
    prm.set("Threads per rank", std::to_string(usable));
    prm.leave_subsection();
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::cout << note;
    phase = "setting up the problem (mesh, finite element spaces, contact surface)";
    ContactProblem<dim> problem(prm, sections);
    if (inf_sup_meshes > 0)
      {
        phase = "running the inf-sup test";
        problem.run_inf_sup_test(inf_sup_meshes);
        return 0;
      }
    phase = resume ? "resuming and running the load steps" : "running the load steps";
    if (problem.run(resume))
      return 0;
    return problem.stopped_at_wall_time_limit() ? 3 : 2;
  }

  /** What the command line asks for, once the options are taken out. */
  struct CommandLine
  {
    std::vector<std::string> files; ///< the parameter file, if any
    std::string              threads;
    bool                     resume         = false;
    unsigned int             inf_sup_meshes = 0;
  };

  /** Take the option @p name out of @p files; whether it was there. */
  bool
  take_flag(std::vector<std::string> &files, const std::string &name)
  {
    const auto found = std::find(files.begin(), files.end(), name);
    if (found == files.end())
      return false;
    files.erase(found);
    return true;
  }

  /**
   * The argument @p text of the option @p name (`--threads N`): an integer
   * from @p min to @p max, else InputError saying so.
   */
  unsigned int
  option_value(const std::string &name,
               const std::string &text,
               const unsigned int min,
               const unsigned int max)
  {
    const auto value = Parameters::decimal_integer(text, max);
    if (!value || *value < min)
      throw InputError(name + " N: N must be an integer from " + std::to_string(min) + " to " +
                       std::to_string(max) + ", got " +
                       (text.empty() ? std::string("an empty argument") : "'" + text + "'") + ".");
    return static_cast<unsigned int>(*value);
  }

  /** --threads N, --resume, --inf-sup [N] and the parameter file. */
  CommandLine
  parse_command_line(const std::vector<std::string> &args)
  {
    CommandLine command;
    command.files     = args;
    auto      &files  = command.files;
    const auto option = std::find(files.begin(), files.end(), "--threads");
    if (option != files.end())
      {
        if (option + 1 == files.end())
          throw InputError("--threads N: N must be an integer from 1 to 256, got nothing.");
        command.threads = std::to_string(option_value("--threads", *(option + 1), 1, 256));
        files.erase(option, option + 2);
      }
    command.resume = take_flag(files, "--resume");
    if (!files.empty() && files[0] == "--inf-sup")
      {
        files.erase(files.begin());
        command.inf_sup_meshes = 4;
        if (files.size() == 2)
          {
            command.inf_sup_meshes = option_value("--inf-sup", files[0], 1, 10);
            files.erase(files.begin());
          }
        if (files.size() != 1)
          throw InputError(std::string("--inf-sup needs a parameter file.\n") + usage);
      }
    for (const auto &argument : files)
      if (argument.rfind("-", 0) == 0)
        throw InputError("unknown option '" + argument + "'.\n" + usage);
    if (files.size() > 1)
      throw InputError("one parameter file at most, got " + std::to_string(files.size()) + ".\n" +
                       usage);
    if (command.resume && (files.empty() || command.inf_sup_meshes > 0))
      throw InputError("--resume needs the parameter file of the run to continue.");
    return command;
  }

  /** What the standard exception @p e says happened, in words. */
  std::string
  failure_in_words(const std::exception &e)
  {
    if (dynamic_cast<const std::out_of_range *>(&e) != nullptr)
      return "a number or an index out of its range";
    if (dynamic_cast<const std::invalid_argument *>(&e) != nullptr)
      return "a value that could not be converted";
    if (dynamic_cast<const std::ios_base::failure *>(&e) != nullptr)
      return "a file that could not be read or written";
    if (dynamic_cast<const std::system_error *>(&e) != nullptr)
      return "a failed call to the operating system";
    if (dynamic_cast<const std::length_error *>(&e) != nullptr)
      return "a container grown beyond its largest size";
    return "an unexpected failure";
  }

  /** --print-parameters [2|3]: every entry with its documentation and default. */
  void
  print_parameters(const std::vector<std::string> &args, const bool root)
  {
    if (args.size() > 2 || (args.size() == 2 && args[1] != "2" && args[1] != "3"))
      throw InputError("--print-parameters takes the dimension, 2 or 3 (default 2), "
                       "and nothing else.\n" +
                       std::string(usage));
    const unsigned int dim = args.size() > 1 && args[1] == "3" ? 3 : 2;
    ParameterHandler   prm;
    if (dim == 3)
      Parameters::declare_all<3>(prm);
    else
      Parameters::declare_all<2>(prm);
    // the listing is a parameter file of its dimension: run as is, it runs there
    prm.set("Dimension", std::to_string(dim));
    if (root)
      prm.print_parameters(std::cout, ParameterHandler::PRM);
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // The log goes out line by line also when it is redirected to a file, so
  // that a run killed (by the user, a batch system, a crash) leaves every
  // line it printed (std::cout writes through C's stdout, synchronised).
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  try
    {
      const std::vector<std::string> args(argv + 1, argv + argc);
      if (!args.empty() && (args[0] == "--help" || args[0] == "-h"))
        {
          if (root)
            std::cout << usage;
          return 0;
        }
      if (!args.empty() && args[0] == "--print-parameters")
        {
          print_parameters(args, root);
          return 0;
        }
      const CommandLine command  = parse_command_line(args);
      phase                      = "reading the parameter file";
      const bool         is_file = !command.files.empty();
      const std::string  text    = is_file ? command.files[0] : std::string(default_scene_prm);
      const unsigned int dim     = Parameters::read_dimension(text, is_file);
      return dim == 2
                 ? run<2>(text, is_file, command.inf_sup_meshes, command.threads, command.resume)
                 : run<3>(text, is_file, command.inf_sup_meshes, command.threads, command.resume);
    }
  catch (const InputError &e)
    {
      if (root)
        std::cerr << "Input error: " << Parameters::located(e.what()) << std::endl;
      return 1;
    }
  catch (const std::bad_alloc &)
    {
      // (on the rank that ran out, which need not be the first)
      struct rlimit limit;
      std::cerr << "Error: out of memory while " << phase
                << (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1
                        ? " on rank " +
                              std::to_string(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD))
                        : std::string())
                << ": an allocation failed"
                << (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY
                        ? " within the address-space limit of " +
                              std::to_string(limit.rlim_cur >> 20) + " MiB (ulimit -v)"
                        : std::string())
                << ". Use a coarser mesh, fewer ranks per node or fewer threads." << std::endl;
      return 1;
    }
  catch (const ExceptionBase &e)
    {
      if (root)
        {
          std::cerr << "Error while " << phase << ": ";
          e.print_info(std::cerr);
          std::cerr << std::endl;
        }
      return 1;
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "Error: " << failure_in_words(e) << " while " << phase
                  << " (the library's message: '" << e.what()
                  << "'). The input was accepted, so this is a failure of the program: please "
                     "report it with the parameter file."
                  << std::endl;
      return 1;
    }
}
