# Imported target GiNaC::GiNaC (GiNaC + CLN) located with pkg-config, since GiNaC ships ginac.pc.
find_package(PkgConfig REQUIRED)
pkg_check_modules(GINAC_PC QUIET IMPORTED_TARGET ginac>=1.8)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(GiNaC
  REQUIRED_VARS GINAC_PC_LINK_LIBRARIES
  VERSION_VAR GINAC_PC_VERSION)
if(GiNaC_FOUND AND NOT TARGET GiNaC::GiNaC)
  add_library(GiNaC::GiNaC INTERFACE IMPORTED)
  target_link_libraries(GiNaC::GiNaC INTERFACE PkgConfig::GINAC_PC)
endif()
