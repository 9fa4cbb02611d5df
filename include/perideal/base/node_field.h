#ifndef perideal_base_node_field_h
#define perideal_base_node_field_h

#include <string>
#include <vector>

namespace PeriDEAL
{
  /**
   * A scalar field with one value per owned node, in the order of
   * NodeSet's owned nodes, and its name in the output. It lives below io/
   * so that models can describe their output fields without depending on
   * the writer; IO::NodeField, which IO::SolutionOutput writes, is this
   * type.
   */
  struct NodeField
  {
    std::string         name;
    std::vector<double> values;
  };
} // namespace PeriDEAL

#endif
