# pge::gmpxx: GMP's C++ interface (gmpxx.h, libgmpxx, libgmp), which the oracle's public headers
# use (pge/oracle_exact.hpp). One imported target for the build tree and for an installed
# package's consumers alike (pgeConfig.cmake includes this file), so that no absolute path of the
# build machine's GMP is written into the exported targets. Debian: libgmp-dev.
if(NOT TARGET pge::gmpxx)
  find_path(PGE_GMPXX_INCLUDE_DIR gmpxx.h)
  find_library(PGE_GMPXX_LIBRARY gmpxx)
  find_library(PGE_GMP_LIBRARY gmp)
  if(PGE_GMPXX_INCLUDE_DIR AND PGE_GMPXX_LIBRARY AND PGE_GMP_LIBRARY)
    add_library(pge::gmpxx UNKNOWN IMPORTED)
    set_target_properties(pge::gmpxx PROPERTIES
      IMPORTED_LOCATION "${PGE_GMPXX_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${PGE_GMPXX_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${PGE_GMP_LIBRARY}")
  endif()
endif()

# pge::arb: Arb's rigorous ball arithmetic (arb.h, libflint-arb) over FLINT (libflint), which the
# oracle's referee for rotating bodies uses in one translation unit (oracle/src/rotating.cpp).
# Linked privately; an installed package's consumers link it too (static libraries). Debian:
# libflint-arb-dev (which brings libflint-dev).
if(NOT TARGET pge::arb)
  find_path(PGE_ARB_INCLUDE_DIR arb.h)
  find_library(PGE_ARB_LIBRARY NAMES flint-arb arb)
  find_library(PGE_FLINT_LIBRARY flint)
  if(PGE_ARB_INCLUDE_DIR AND PGE_ARB_LIBRARY AND PGE_FLINT_LIBRARY AND TARGET pge::gmpxx)
    add_library(pge::arb UNKNOWN IMPORTED)
    set_target_properties(pge::arb PROPERTIES
      IMPORTED_LOCATION "${PGE_ARB_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${PGE_ARB_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${PGE_FLINT_LIBRARY};pge::gmpxx")
  endif()
endif()
