#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <default_scene.h>

#include <algorithm>
#include <iostream>

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
                       Linear solver/Threads per rank, 1); the environment's
                       OPENBLAS_NUM_THREADS and OMP_NUM_THREADS are ignored
  --inf-sup [N]        numerical inf-sup test of the scene's FE pair on its mesh
                       and N - 1 global refinements (default N = 4): beta_h per
                       mesh, printed and written to inf_sup.csv; one MPI rank
  --print-parameters   list every entry with its documentation and default
                       (for dimension 2, or the dimension given)
  --help               this text

Output goes to the directory of the entry Output/Output directory.
)";

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
    Parameters::parse<dim>(prm, text, is_file);
    if (!threads.empty())
      {
        prm.enter_subsection("Linear solver");
        prm.set("Threads per rank", threads);
        prm.leave_subsection();
      }
    ContactProblem<dim> problem(prm);
    if (inf_sup_meshes > 0)
      {
        problem.run_inf_sup_test(inf_sup_meshes);
        return 0;
      }
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
        if (option + 1 == files.end() ||
            (option + 1)->find_first_not_of("0123456789") != std::string::npos ||
            (option + 1)->size() > 3 || std::stoi(*(option + 1)) < 1 ||
            std::stoi(*(option + 1)) > 256)
          throw InputError("--threads N: N must be an integer from 1 to 256.");
        command.threads = *(option + 1);
        files.erase(option, option + 2);
      }
    command.resume = take_flag(files, "--resume");
    if (!files.empty() && files[0] == "--inf-sup")
      {
        files.erase(files.begin());
        command.inf_sup_meshes = 4;
        if (files.size() == 2)
          {
            if (files[0].find_first_not_of("0123456789") != std::string::npos ||
                std::stoi(files[0]) < 1 || std::stoi(files[0]) > 10)
              throw InputError("--inf-sup N: N must be an integer from 1 to 10, got '" + files[0] +
                               "'.");
            command.inf_sup_meshes = std::stoi(files[0]);
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

  /** --print-parameters [2|3]: every entry with its documentation and default. */
  void
  print_parameters(const std::vector<std::string> &args, const bool root)
  {
    if (args.size() > 2 || (args.size() == 2 && args[1] != "2" && args[1] != "3"))
      throw InputError("--print-parameters takes the dimension, 2 or 3 (default 2), "
                       "and nothing else.\n" +
                       std::string(usage));
    const unsigned int dim = args.size() > 1 ? std::stoi(args[1]) : 2;
    ParameterHandler   prm;
    if (dim == 3)
      Parameters::declare_all<3>(prm);
    else
      Parameters::declare_all<2>(prm);
    if (root)
      prm.print_parameters(std::cout, ParameterHandler::PRM);
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool                       root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
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
      const CommandLine  command = parse_command_line(args);
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
        std::cerr << "Input error: " << e.what() << std::endl;
      return 1;
    }
  catch (const ExceptionBase &e)
    {
      if (root)
        {
          std::cerr << "Error: ";
          e.print_info(std::cerr);
          std::cerr << std::endl;
        }
      return 1;
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "Error: " << e.what() << std::endl;
      return 1;
    }
}
