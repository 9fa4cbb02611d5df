// perideal: runs the PD problem (any registered problem type) described by a
// parameter file.
//
//   perideal input.prm             run (under mpirun for several processes)
//   perideal --threads N input.prm  with N threads per process (default:
//                                   the cores of the machine shared among
//                                   the processes on it)
//   perideal --print-parameters    every entry with its default and help
//   perideal --help                usage

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <perideal/base/shared_libraries.h>
#include <perideal/problems/simulator.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace dealii;

namespace
{
  // An error whose message is meant for the user as it is.
  struct InputError : public std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };


  // deal.II's exceptions carry the source location and condition; users
  // need the "additional information" only.
  std::string
  user_message(const dealii::ExceptionBase &exc)
  {
    std::ostringstream info;
    exc.print_info(info);
    return info.str();
  }


  // ParameterHandler's errors name an entry without its subsection ("Line
  // <5> of file <a.prm>: ... the entry named Subdivisions does not match
  // the given pattern ..."; "No entry with name <m-ration> was declared").
  // Said again in PeriDEAL's form, with the entry's path and value read from
  // that line of the file; other messages are returned as they are.
  std::string
  explain_parse_error(const std::string &file, const std::string &message)
  {
    const std::string line_tag = "Line <";
    const auto        at       = message.find(line_tag);
    if (at == std::string::npos)
      return message;
    const unsigned int number =
      std::strtoul(message.c_str() + at + line_tag.size(), nullptr, 10);
    std::ifstream            in(file);
    std::string              text, name, value;
    std::vector<std::string> path;
    for (unsigned int n = 1; n <= number && std::getline(in, text); ++n)
      {
        text = Utilities::trim(text.substr(0, text.find('#')));
        if (text.rfind("subsection ", 0) == 0)
          path.push_back(Utilities::trim(text.substr(11)));
        else if (text == "end" && !path.empty())
          path.pop_back();
        else if (n == number && text.rfind("set ", 0) == 0 &&
                 text.find('=') != std::string::npos)
          {
            const auto equal = text.find('=');
            name             = Utilities::trim(text.substr(4, equal - 4));
            value            = Utilities::trim(text.substr(equal + 1));
          }
      }
    if (name.empty())
      return message;
    for (auto p = path.rbegin(); p != path.rend(); ++p)
      name = *p + "/" + name;
    const std::string where =
      " (line " + std::to_string(number) + " of '" + file + "')";
    if (message.find("No entry with name") != std::string::npos)
      return "The entry '" + name + "' = '" + value + "'" + where +
             " is not declared: check its spelling and its subsection; "
             "'perideal --print-parameters' lists every entry.\n";
    const std::string pattern_tag = "does not match the given pattern:";
    const auto        pattern     = message.find(pattern_tag);
    if (pattern == std::string::npos)
      return message;
    return "Invalid value '" + value + "' for the parameter '" + name +
           "': it does not match the allowed form " +
           Utilities::trim(message.substr(pattern + pattern_tag.size())) +
           where + ".\n";
  }


  void
  print_usage(std::ostream &out)
  {
    out << "Usage: perideal [--threads N] <input.prm>\n"
           "       perideal --print-parameters [1|2|3]\n"
           "       perideal --help\n\n"
           "Runs the peridynamic problem described by the\n"
           "deal.II parameter file <input.prm> (run it under mpirun for\n"
           "several MPI processes). --print-parameters prints every entry,\n"
           "with its default, allowed values and help text, for 3D (or the\n"
           "dimension given). Examples are in the directory parameters/.\n"
           "--threads N sets the threads per process of the bond loops\n"
           "(default: the machine's cores shared among its processes).\n";
  }


  // The dimension is read first, from the top-level entry "Dimension"; the
  // full parse (which rejects unknown entries) follows once it is known.
  unsigned int
  read_dimension(const std::string &file)
  {
    ParameterHandler prm;
    prm.declare_entry("Dimension", "3", Patterns::Integer(1, 3));
    prm.declare_entry("Problem type", "", Patterns::Anything());
    try
      {
        prm.parse_input(file, "", /*skip_undefined*/ true);
      }
    catch (const ExceptionBase &exc)
      {
        throw InputError(explain_parse_error(file, user_message(exc)));
      }
    const unsigned int dim = prm.get_integer("Dimension");
    // 1D has fewer problem types than 2D and 3D: say so, rather than let
    // the full parse report only the pattern.
    const std::string problem = prm.get("Problem type");
    if (dim == 1 && !problem.empty() &&
        !PeriDEAL::Problems::ProblemTypeRegistry<1>::is_registered(problem))
      throw InputError(
        "Invalid value '" + problem +
        "' for the parameter 'Problem type': 1D runs ('Dimension = 1') "
        "offer only " +
        PeriDEAL::Problems::ProblemTypeRegistry<1>::pattern_string() +
        "; set 'Dimension = 2' or 3, or choose a 1D problem type.\n");
    return dim;
  }


  template <int dim>
  void
  run(const std::string &file)
  {
    ParameterHandler prm;
    PeriDEAL::Problems::Simulator<dim>::declare_parameters(prm);
    try
      {
        prm.parse_input(file);
      }
    catch (const ExceptionBase &exc)
      {
        throw InputError(explain_parse_error(file, user_message(exc)));
      }
    PeriDEAL::Problems::Simulator<dim>::check_input_file(file, prm);
    // The simulation is destroyed before an error propagates: its timer
    // then finishes quietly instead of warning about an exception in flight.
    std::string other_error;
    {
      PeriDEAL::Problems::Simulator<dim> simulation(MPI_COMM_WORLD);
      try
        {
          simulation.parse_parameters(prm);
          simulation.run();
        }
      catch (const dealii::ExceptionBase &exc)
        {
          other_error = user_message(exc);
        }
      catch (const std::bad_alloc &)
        {
          throw;
        }
      catch (const std::exception &exc)
        {
          other_error = exc.what();
        }
    }
    if (!other_error.empty())
      throw InputError(other_error);
  }


  template <int dim>
  void
  print_parameters()
  {
    ParameterHandler prm;
    PeriDEAL::Problems::Simulator<dim>::declare_parameters(prm);
    // The listing must run as it is: it names its own dimension.
    prm.set("Dimension", std::to_string(dim));
    prm.print_parameters(std::cout, ParameterHandler::PRM);
  }
} // namespace


int
main(int argc, char **argv)
{
  // "--threads N" is taken out of the arguments before anything else; the
  // thread pool is sized when MPI starts.
  unsigned int        n_threads = numbers::invalid_unsigned_int;
  std::string         threads_error;
  std::vector<char *> args = {argv[0]};
  for (int a = 1; a < argc; ++a)
    if (std::string(argv[a]) == "--threads")
      {
        int n = 0;
        if (a + 1 < argc)
          {
            std::istringstream in(argv[a + 1]);
            in >> n;
            if (!in || !in.eof())
              n = 0;
          }
        if (n < 1)
          threads_error =
            "perideal: --threads takes a positive integer, not '" +
            std::string(a + 1 < argc ? argv[a + 1] : "") + "'.";
        else
          n_threads = n;
        ++a;
      }
    else
      args.push_back(argv[a]);
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, n_threads);
  argc            = args.size();
  argv            = args.data();
  const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  if (!threads_error.empty())
    {
      if (root)
        std::cerr << threads_error << std::endl;
      return 1;
    }
  try
    {
      const std::string first = argc > 1 ? argv[1] : "";
      if (argc < 2 || first == "--help" || first == "-h")
        {
          if (root)
            print_usage(argc < 2 ? std::cerr : std::cout);
          return argc < 2 ? 1 : 0;
        }
      if (first == "--print-parameters")
        {
          const std::string dim = argc > 2 ? argv[2] : "3";
          if (dim != "1" && dim != "2" && dim != "3")
            {
              if (root)
                std::cerr
                  << "perideal: --print-parameters takes 1, 2 or 3, not '"
                  << dim << "'." << std::endl;
              return 1;
            }
          if (root)
            {
              if (dim == "1")
                print_parameters<1>();
              else if (dim == "2")
                print_parameters<2>();
              else
                print_parameters<3>();
            }
          return 0;
        }
      if (argc > 2 || first.rfind("-", 0) == 0)
        {
          if (root)
            {
              std::cerr << "perideal: unexpected arguments.\n";
              print_usage(std::cerr);
            }
          return 1;
        }

      if (!std::filesystem::is_regular_file(first) ||
          !std::ifstream(first).good())
        throw InputError("Cannot read the parameter file '" + first +
                         "': no such readable file. Give the path of a .prm "
                         "file; examples are in parameters/.\n");
      // A user's plugins register themselves when their library is loaded:
      // before anything is declared, so that their names are selectable.
      PeriDEAL::load_shared_libraries(first, MPI_COMM_WORLD);
      const unsigned int dim = read_dimension(first);
      if (dim == 1)
        run<1>(first);
      else if (dim == 2)
        run<2>(first);
      else
        run<3>(first);
    }
  catch (const std::bad_alloc &)
    {
      // Out of memory on this process: say so on every process that gets
      // here (another may be waiting for it; MPI then ends the job).
      std::cerr << "\nperideal: error (process "
                << Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)
                << ")\n    Out of memory. Use fewer cells, 'Linear "
                   "solver/Operator = matrix-free' (about 2 KB per node "
                   "instead of the assembled matrix), or more machines."
                << std::endl;
      if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        MPI_Abort(MPI_COMM_WORLD, 1);
      return 1;
    }
  catch (const std::exception &exc)
    {
      const auto *deal_exception =
        dynamic_cast<const dealii::ExceptionBase *>(&exc);
      if (root)
        std::cerr << "\nperideal: error\n"
                  << (deal_exception ? user_message(*deal_exception) :
                                       std::string(exc.what()))
                  << std::endl;
      // Input errors are found alike on every process (each reads the whole
      // file; checks that need global data reduce it first), so all
      // processes end here and leave together.
      return 1;
    }
  return 0;
}
