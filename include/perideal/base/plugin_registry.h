#ifndef perideal_base_plugin_registry_h
#define perideal_base_plugin_registry_h

#include <deal.II/base/parameter_handler.h>

#include <perideal/base/exceptions.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace internal
  {
    /**
     * Registration errors of the shared library being loaded. A plugin in a
     * user's library registers while dlopen() runs the library's static
     * initialisers, and an exception cannot pass through dlopen() (the
     * program would terminate): while @p collect is set (by
     * load_shared_libraries()), PluginRegistry::register_class() records
     * its errors here instead of throwing, and the loader reports them.
     */
    struct RegistrationErrors
    {
      bool                     collect = false;
      std::vector<std::string> messages;
    };

    /// The one RegistrationErrors object of the program.
    RegistrationErrors &
    registration_errors();
  } // namespace internal


  /**
   * A name-to-factory registry for one family of interchangeable classes
   * (partial-volume algorithms, material models, boundary treatments, ...),
   * in the spirit of ASPECT's plugin system: each class registers itself in
   * its own translation unit with a name, a description (which also feeds the
   * documentation and `--help` texts), a function that declares its
   * parameters and a factory. Adding a class never touches a central switch.
   *
   * Parameters of a registered class live in a subsection named after the
   * class's registered name, inside whatever subsection the caller has
   * entered.
   *
   * @tparam Interface The abstract base class of the family. It must have a
   * member function `void parse_parameters(dealii::ParameterHandler &)`.
   */
  template <class Interface>
  class PluginRegistry
  {
  public:
    /// Declares the parameters of one registered class.
    using ParameterDeclaration =
      std::function<void(dealii::ParameterHandler &)>;

    /// Creates an object of one registered class with default parameters.
    using Factory = std::function<std::unique_ptr<Interface>()>;

    /**
     * Register a class. Called through the registration macros at static
     * initialisation time; returns true so that the result can initialise a
     * static variable.
     */
    static bool
    register_class(const std::string          &name,
                   const std::string          &description,
                   const ParameterDeclaration &declare_parameters,
                   const Factory              &factory);

    /// All registered names, sorted.
    static std::vector<std::string>
    names();

    /// All registered names as a deal.II pattern string "a|b|c".
    static std::string
    pattern_string();

    /// The description a class was registered with.
    static const std::string &
    description(const std::string &name);

    /// Whether @p name is registered.
    static bool
    is_registered(const std::string &name);

    /**
     * Declare one subsection per registered class, holding its parameters.
     */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /**
     * Create the class registered as @p name with its default parameters.
     * Throws ExcUnknownName listing the registered names otherwise.
     */
    static std::unique_ptr<Interface>
    create(const std::string &name);

    /**
     * Create the class registered as @p name and let it read its parameters
     * from the subsection named @p name of @p prm (which must have been
     * declared with declare_parameters()).
     */
    static std::unique_ptr<Interface>
    create(const std::string &name, dealii::ParameterHandler &prm);

  private:
    struct Entry
    {
      std::string          description;
      ParameterDeclaration declare_parameters;
      Factory              factory;
    };

    static std::map<std::string, Entry> &
    entries();

    static const Entry &
    find(const std::string &name);
  };


  template <class Interface>
  std::map<std::string, typename PluginRegistry<Interface>::Entry> &
  PluginRegistry<Interface>::entries()
  {
    // A function-local static avoids the static initialisation order problem
    // between registrations in different translation units.
    static std::map<std::string, Entry> registered;
    return registered;
  }


  template <class Interface>
  bool
  PluginRegistry<Interface>::register_class(
    const std::string          &name,
    const std::string          &description,
    const ParameterDeclaration &declare_parameters,
    const Factory              &factory)
  {
    if (entries().count(name) != 0)
      {
        const std::string message =
          "The " + Interface::family_name() + " '" + name +
          "' is registered twice: a plugin needs a name that no built-in "
          "class and no other loaded library uses.";
        if (internal::registration_errors().collect)
          {
            internal::registration_errors().messages.push_back(message);
            return false;
          }
        AssertThrow(false, dealii::ExcMessage(message));
      }
    entries()[name] = Entry{description, declare_parameters, factory};
    return true;
  }


  template <class Interface>
  std::vector<std::string>
  PluginRegistry<Interface>::names()
  {
    std::vector<std::string> result;
    for (const auto &entry : entries())
      result.push_back(entry.first);
    return result;
  }


  template <class Interface>
  std::string
  PluginRegistry<Interface>::pattern_string()
  {
    std::string result;
    for (const auto &entry : entries())
      result += (result.empty() ? "" : "|") + entry.first;
    return result;
  }


  template <class Interface>
  bool
  PluginRegistry<Interface>::is_registered(const std::string &name)
  {
    return entries().count(name) > 0;
  }


  template <class Interface>
  const typename PluginRegistry<Interface>::Entry &
  PluginRegistry<Interface>::find(const std::string &name)
  {
    const auto entry = entries().find(name);
    AssertThrow(entry != entries().end(),
                ExcUnknownName(Interface::family_name(),
                               name,
                               pattern_string()));
    return entry->second;
  }


  template <class Interface>
  const std::string &
  PluginRegistry<Interface>::description(const std::string &name)
  {
    return find(name).description;
  }


  template <class Interface>
  void
  PluginRegistry<Interface>::declare_parameters(dealii::ParameterHandler &prm)
  {
    for (const auto &entry : entries())
      {
        prm.enter_subsection(entry.first);
        entry.second.declare_parameters(prm);
        prm.leave_subsection();
      }
  }


  template <class Interface>
  std::unique_ptr<Interface>
  PluginRegistry<Interface>::create(const std::string &name)
  {
    return find(name).factory();
  }


  template <class Interface>
  std::unique_ptr<Interface>
  PluginRegistry<Interface>::create(const std::string        &name,
                                    dealii::ParameterHandler &prm)
  {
    std::unique_ptr<Interface> object = create(name);
    prm.enter_subsection(name);
    object->parse_parameters(prm);
    prm.leave_subsection();
    return object;
  }
} // namespace PeriDEAL

#define PERIDEAL_CONCAT_IMPL(a, b) a##b
#define PERIDEAL_CONCAT(a, b) PERIDEAL_CONCAT_IMPL(a, b)

/**
 * Register @p Class (derived from @p Interface) under @p name. Use once, in
 * the class's own source file, at namespace scope. @p Class must provide
 * `static void declare_parameters(dealii::ParameterHandler &)` and a default
 * constructor.
 */
#define PERIDEAL_REGISTER_CLASS(Interface, Class, name, description)           \
  namespace                                                                    \
  {                                                                            \
    const bool PERIDEAL_CONCAT(perideal_registered_, __COUNTER__) =            \
      ::PeriDEAL::PluginRegistry<Interface>::register_class(                   \
        name,                                                                  \
        description,                                                           \
        [](dealii::ParameterHandler &prm) { Class::declare_parameters(prm); }, \
        []() -> std::unique_ptr<Interface> {                                   \
          return std::make_unique<Class>();                                    \
        });                                                                    \
  }

#endif
