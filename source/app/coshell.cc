// coshell: runs one scene (a .prm file) and writes VTU/PVD, summary.json
// and, for refinement studies, convergence.csv.

#include <coshell/base/parallel_environment.h>
#include <coshell/driver/interruption.h>
#include <coshell/driver/scene.h>

#include <cstring>
#include <iostream>
#include <streambuf>
#include <string>
#include <vector>

namespace
{
  const char *usage =
      "usage: coshell FILE.prm [--set \"Section/Name=value\" ...] "
      "[--output DIR] [--interactive] [--restart FILE]\n"
      "       coshell --print-parameters [FILE.prm]\n"
      "       coshell --print-parameters-json\n"
      "       coshell --help\n"
      "\n"
      "  FILE.prm              scene parameter file (deal.II ParameterHandler "
      "format)\n"
      "  --set \"A/B/Name=v\"    override one parameter (repeatable)\n"
      "  --output DIR          write results to DIR (default: "
      "Output/Directory)\n"
      "  --print-parameters    print every parameter with its default and\n"
      "                        documentation, in .prm form (with FILE.prm: "
      "its\n"
      "                        values)\n"
      "  --print-parameters-json  every parameter with its default, accepted\n"
      "                        values and documentation, as JSON (the source\n"
      "                        of doc/parameters.md)\n"
      "  --interactive         dynamic stages advance to the times read "
      "from\n"
      "                        standard input, one per line; one line per "
      "step\n"
      "                        on standard output (protocol:\n"
      "                        doc/user-guide/interactive.md)\n"
      "  --restart FILE        resume from a checkpoint (HDF5) written by\n"
      "                        Output/Checkpoint interval or on SIGINT/"
      "SIGTERM\n"
      "  --help                this text\n"
      "\n"
      "Exit status: 0 on success, 1 on bad input or a failed solve, 2 on a "
      "bad command line,\n3 when stopped by SIGINT or SIGTERM (a dynamic "
      "stage writes a checkpoint first).\n";

  struct CommandLine
  {
    std::string              prm_file;
    std::vector<std::string> overrides;
    std::string              output_directory;
    std::string              restart_file;
    bool                     help             = false;
    bool                     print_parameters = false;
    bool                     print_json       = false;
    bool                     interactive      = false;
  };

  CommandLine parse_command_line(int argc, char **argv)
  {
    CommandLine line;
    for (int i = 1; i < argc; ++i)
    {
      const std::string arg       = argv[i];
      const bool        has_value = i + 1 < argc;
      if (arg == "--help" || arg == "-h")
        line.help = true;
      else if (arg == "--interactive")
        line.interactive = true;
      else if (arg == "--print-parameters")
        line.print_parameters = true;
      else if (arg == "--print-parameters-json")
        line.print_parameters = line.print_json = true;
      else if (arg == "--set" && has_value)
        line.overrides.push_back(argv[++i]);
      else if (arg == "--output" && has_value)
        line.output_directory = argv[++i];
      else if (arg == "--restart" && has_value)
        line.restart_file = argv[++i];
      else if (arg.rfind("-", 0) != 0 && line.prm_file.empty())
        line.prm_file = arg;
      else
        throw std::invalid_argument("unexpected argument '" + arg + "'");
    }
    return line;
  }
} // namespace

namespace
{
  /// A stream buffer that drops what is written to it.
  class DiscardingBuffer : public std::streambuf
  {
  protected:
    int overflow(int c) override
    {
      return c;
    }
  };

  /// The prm's Output/Directory as written (parse_parameters takes it
  /// as it is, relative to the working directory).
  std::string output_entry(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    const std::string directory = prm.get("Directory");
    prm.leave_subsection();
    return directory;
  }

  /// Reads the parameters and runs the scene the command line names
  /// (or prints the parameters); throws on bad input or a failed solve.
  /// 'output' is set to the output directory as soon as it is known.
  int read_and_run_scene(const CommandLine &line, std::string &output)
  {
    dealii::ParameterHandler prm;
    coshell::driver::Scene::declare_parameters(prm);
    if (!line.prm_file.empty())
      coshell::driver::read_parameters(prm, line.prm_file, line.overrides);
    if (line.print_parameters)
    {
      prm.print_parameters(std::cout, line.print_json
                                          ? dealii::ParameterHandler::JSON
                                          : dealii::ParameterHandler::PRM);
      return 0;
    }
    if (output.empty())
      output = output_entry(prm);
    coshell::driver::Scene scene;
    scene.parse_parameters(prm, line.prm_file);
    // Interactive runs keep standard output for the protocol; the log
    // goes to standard error.
    std::ostream &log = line.interactive ? std::cerr : std::cout;
    if (line.interactive && !line.restart_file.empty())
      throw std::invalid_argument("--restart and --interactive do not go "
                                  "together");
    if (line.interactive && coshell::base::distributed())
      throw std::invalid_argument("--interactive runs on one rank; start it "
                                  "without mpirun");
    if (line.interactive)
      scene.drive_interactively(std::cin, std::cout);
    if (!line.restart_file.empty())
      scene.restart_from(line.restart_file);
    coshell::driver::install_interrupt_handlers();
    scene.run(output, log);
    log << "results written to " << output << "\n";
    return 0;
  }

  /// read_and_run_scene; a run refused for its input (a bad parameter, a
  /// missing checkpoint) also removes an earlier run's summary from the
  /// output directory, as Scene::run does for a run that fails. Before the
  /// prm is read that directory is known only from --output.
  int run_scene(const CommandLine &line)
  {
    std::string output = line.output_directory;
    try
    {
      return read_and_run_scene(line, output);
    }
    catch (const coshell::driver::Interrupted &)
    {
      throw; // a stopped run is not a refused one; it wrote a checkpoint
    }
    catch (const std::exception &)
    {
      if (!output.empty())
        coshell::driver::Scene::forget_results(output);
      throw;
    }
  }
} // namespace

namespace
{
  /// Prints 'message' on standard error and returns 'status'. Under mpirun
  /// a failure every rank shares is printed once, by rank 0; one on some
  /// ranks only is printed by each of them, which then end the others
  /// (they may wait in a collective for ever).
  int report_failure(const std::string &message, int status)
  {
    const bool every_rank = coshell::base::every_rank_stops();
    if (!every_rank || coshell::base::writes_output())
      std::cerr << message << std::flush;
    if (!every_rank)
      coshell::base::abort_other_ranks(status);
    return status;
  }
} // namespace

int main(int argc, char **argv)
{
  // Serial runs start MPI lazily (see ensure_mpi_initialized).
  if (coshell::base::launched_by_mpi_launcher())
    coshell::base::ensure_mpi_initialized();
  // Under mpirun every rank runs the scene; rank 0 alone logs and writes.
  if (!coshell::base::writes_output())
    std::cout.rdbuf(new DiscardingBuffer); // lives as long as std::cout
  CommandLine line;
  try
  {
    line = parse_command_line(argc, argv);
    if (line.help || (line.prm_file.empty() && !line.print_parameters))
    {
      std::cout << usage;
      return line.help ? 0 : 2;
    }
  }
  catch (const std::exception &error)
  {
    return report_failure(
        "coshell: " + std::string(error.what()) + "\n\n" + usage, 2);
  }

  try
  {
    return run_scene(line);
  }
  catch (const coshell::driver::Interrupted &stop)
  {
    // The ranks agree on a signal, so all of them stop here.
    return report_failure("coshell: " + std::string(stop.what()) + "\n", 3);
  }
  catch (const std::exception &error)
  {
    return report_failure("coshell: error: " + std::string(error.what()) + "\n",
                          1);
  }
}
