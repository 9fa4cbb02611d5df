#ifndef perideal_io_solution_output_h
#define perideal_io_solution_output_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/trilinos_vector.h>

#include <perideal/base/node_field.h>
#include <perideal/discretization/node_set.h>
#include <perideal/io/output_names.h>

#include <string>
#include <utility>
#include <vector>

namespace PeriDEAL
{
  /**
   * Output for ParaView and summaries of runs.
   */
  namespace IO
  {
    using namespace dealii;

    /// A scalar field per owned node and its name (PeriDEAL::NodeField, in
    /// base/ so that models can describe their fields without the writer).
    using NodeField = PeriDEAL::NodeField;

    /**
     * Writes a PD solution as VTU pieces (one per process) with a PVTU
     * record for ParaView: the displacement as a vector field and any
     * number of per-node scalar fields, each as cell data on the cell of its
     * node. Reads the subsection "Output" (directory, base name, whether to
     * write at all).
     */
    /// A vector field given by its DoF values (velocity, say), for output.
    struct NodeVector
    {
      std::string                          name;
      const TrilinosWrappers::MPI::Vector *values;
    };

    template <int dim>
    class SolutionOutput
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm);

      /**
       * Write the fields as <base name>_<index>.pvtu with one
       * <base name>_<index>.<rank>.vtu per process (@p vectors: further
       * vector fields of DoF values, such as the velocity); returns the name
       * of the PVTU record (empty if writing is switched off). The output
       * directory is created if missing.
       */
      std::string
      write(const DoFHandler<dim>               &dof_handler,
            const Discretization::NodeSet<dim>  &nodes,
            const TrilinosWrappers::MPI::Vector &displacement,
            const std::vector<NodeField>        &fields,
            const unsigned int                   index   = 0,
            const std::vector<NodeVector>       &vectors = {}) const;

      /**
       * Write the cell fields @p fields alone (no displacement: scalar
       * problems such as diffusion), as record @p index; otherwise as
       * above.
       */
      std::string
      write(const DoFHandler<dim>              &dof_handler,
            const Discretization::NodeSet<dim> &nodes,
            const std::vector<NodeField>       &fields,
            const unsigned int                  index) const;

      /**
       * Write <base name>.pvd, the time series of the given (time, record)
       * pairs that ParaView opens as an animation, on rank 0 under a
       * temporary name (collective). Returns its name, or "" when output is
       * off.
       */
      std::string
      write_time_series(
        const std::vector<std::pair<double, std::string>> &records,
        const MPI_Comm                                     comm) const;

      const std::string &
      directory() const;

      /**
       * The names this output writes, for check_output_names(): the
       * records (<base name>_<n>.pvtu and their pieces) and, with
       * @p time_series, the time series <base name>.pvd; nothing when
       * 'Write VTU' is off.
       */
      std::vector<OutputName>
      output_names(const bool time_series) const;

      /// Whether VTU output is written ('Write VTU').
      bool
      enabled() const
      {
        return write_vtu;
      }

    private:
      /// write() with an optional displacement.
      std::string
      write_record(const DoFHandler<dim>               &dof_handler,
                   const Discretization::NodeSet<dim>  &nodes,
                   const TrilinosWrappers::MPI::Vector *displacement,
                   const std::vector<NodeField>        &fields,
                   const unsigned int                   index,
                   const std::vector<NodeVector>       &vectors) const;

      bool        write_vtu = true;
      std::string output_directory;
      std::string base_name;
    };
  } // namespace IO
} // namespace PeriDEAL

#endif
