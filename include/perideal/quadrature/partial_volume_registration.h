#ifndef perideal_quadrature_partial_volume_registration_h
#define perideal_quadrature_partial_volume_registration_h

#include <perideal/quadrature/partial_volume.h>

/**
 * Register the partial-volume algorithm @p Class (a template over dim) for
 * dim = 2 and 3 under @p name, with one description.
 */
#define PERIDEAL_REGISTER_PARTIAL_VOLUME_2D_3D(Class, name, description) \
  PERIDEAL_REGISTER_PARTIAL_VOLUME(Class, 2, name, description)          \
  PERIDEAL_REGISTER_PARTIAL_VOLUME(Class, 3, name, description)

/**
 * Register the partial-volume algorithm @p Class (a template over dim) for
 * dim = 1, 2 and 3 under @p name, with the description of each dimension.
 */
#define PERIDEAL_REGISTER_PARTIAL_VOLUME_1D_2D_3D(Class,           \
                                                  name,            \
                                                  description_1d,  \
                                                  description_2d,  \
                                                  description_3d)  \
  PERIDEAL_REGISTER_PARTIAL_VOLUME(Class, 1, name, description_1d) \
  PERIDEAL_REGISTER_PARTIAL_VOLUME(Class, 2, name, description_2d) \
  PERIDEAL_REGISTER_PARTIAL_VOLUME(Class, 3, name, description_3d)

#endif
