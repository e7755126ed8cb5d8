# Locates SUNDIALS CVODE with the serial N_Vector and the dense linear solver.
# Debian's SUNDIALSConfig.cmake lists targets (Fortran modules, PETSc, ...) whose files the -dev
# package does not ship, so the libraries are looked up directly and wrapped in one imported target.
find_path(SUNDIALS_INCLUDE_DIR cvode/cvode.h REQUIRED)
find_library(SUNDIALS_CVODE_LIBRARY sundials_cvode REQUIRED)
find_library(SUNDIALS_NVECSERIAL_LIBRARY sundials_nvecserial REQUIRED)
find_library(SUNDIALS_SUNMATDENSE_LIBRARY sundials_sunmatrixdense REQUIRED)
find_library(SUNDIALS_SUNLINSOLDENSE_LIBRARY sundials_sunlinsoldense REQUIRED)
if(NOT TARGET Sundials::cvode)
  add_library(Sundials::cvode INTERFACE IMPORTED)
  set_target_properties(Sundials::cvode PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${SUNDIALS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${SUNDIALS_CVODE_LIBRARY};${SUNDIALS_NVECSERIAL_LIBRARY};${SUNDIALS_SUNLINSOLDENSE_LIBRARY};${SUNDIALS_SUNMATDENSE_LIBRARY}")
endif()
message(STATUS "SUNDIALS CVODE: ${SUNDIALS_CVODE_LIBRARY}")
