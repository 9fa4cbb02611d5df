#ifndef perideal_problems_diffusion_instantiate_h
#define perideal_problems_diffusion_instantiate_h

/**
 * Expand @p MACRO(dim) for dim = 1, 2, 3: the explicit instantiations of
 * the diffusion problem type's members, which are spread over its source
 * files by job (each file lists its own members in a local macro).
 */
#define PERIDEAL_DIFFUSION_INSTANTIATE(MACRO) MACRO(1) MACRO(2) MACRO(3)

#endif
