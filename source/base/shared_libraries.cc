#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/base/plugin_registry.h>
#include <perideal/base/shared_libraries.h>

#include <dlfcn.h>

#include <sstream>

namespace PeriDEAL
{
  namespace
  {
    const std::string entry_name = "Additional shared libraries";


    /**
     * Load one library; returns an empty string or what went wrong,
     * including the registration errors of its plugins (a name that is
     * already registered), which cannot be thrown through dlopen().
     */
    std::string
    load_one(const std::string &name)
    {
      internal::RegistrationErrors &registration =
        internal::registration_errors();
      registration.collect = true;
      registration.messages.clear();
      const bool loaded =
        dlopen(name.c_str(), RTLD_NOW | RTLD_GLOBAL) != nullptr;
      registration.collect = false;
      // ExcInvalidInput ends the sentence.
      auto sentence = [](std::string text) {
        while (!text.empty() &&
               (text.back() == '\n' || text.back() == ' ' ||
                text.back() == '.'))
          text.pop_back();
        return text;
      };
      if (!loaded)
        {
          const char *error = dlerror();
          return "the library could not be loaded (" +
                 sentence(error != nullptr ? error : "no reason given") +
                 "). Give the path of a shared library built against this "
                 "PeriDEAL, relative to the working directory or absolute" +
                 (name.find('/') == std::string::npos ?
                    ": a name without '/' is looked for only in "
                    "LD_LIBRARY_PATH and the system's library directories; "
                    "write './" +
                      name + "' for a library in the working directory" :
                    std::string());
        }
      if (!registration.messages.empty())
        {
          std::string messages;
          for (const std::string &message : registration.messages)
            messages += (messages.empty() ? "" : " ") + message;
          return "its plugins could not be registered (" + sentence(messages) +
                 "). Rename the plugin in its PERIDEAL_REGISTER_* call";
        }
      return "";
    }
  } // namespace


  void
  declare_shared_library_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry(
      entry_name,
      "",
      dealii::Patterns::List(dealii::Patterns::FileName(),
                             0,
                             dealii::Patterns::List::max_int_value,
                             ","),
      "Shared libraries with your own plugins (material models, influence "
      "functions, problem types, boundary treatments, partial-volume "
      "algorithms), loaded on every process before the rest of this file "
      "is read, so that their names can be selected and their parameters "
      "set like those of the built-in ones. A comma-separated list of "
      "paths, relative to the working directory or absolute: "
      "'./libmy_model.so' (a name without '/' is looked for in "
      "LD_LIBRARY_PATH and the system's directories only). Build them "
      "against the installed PeriDEAL (find_package(PeriDEAL), link "
      "PeriDEAL::perideal); see examples/external-plugin and "
      "doc/plugins.md.");
  }


  std::vector<std::string>
  read_shared_library_names(const std::string &parameter_file)
  {
    dealii::ParameterHandler prm;
    declare_shared_library_parameters(prm);
    prm.parse_input(parameter_file, "", /*skip_undefined*/ true);
    std::vector<std::string> names;
    for (const std::string &name :
         dealii::Utilities::split_string_list(prm.get(entry_name)))
      if (!name.empty())
        names.push_back(name);
    return names;
  }


  void
  load_shared_libraries(const std::vector<std::string> &names,
                        const MPI_Comm                  comm)
  {
    for (const std::string &name : names)
      {
        const std::string why = load_one(name);
        check_on_all_ranks(
          [&]() {
            AssertThrow(why.empty(), ExcInvalidInput(entry_name, name, why));
          },
          comm);
      }
  }


  void
  load_shared_libraries(const std::string &parameter_file,
                        const MPI_Comm     comm)
  {
    load_shared_libraries(read_shared_library_names(parameter_file), comm);
  }
} // namespace PeriDEAL
