# Two HDF5 libraries of one version and one API, chosen per executable:
#   kimp_hdf5_parallel   the one found by find_package(HDF5) (OpenMPI flavour on Debian), which
#                        deal.II links: every target but the lean `kimp`, so that one process
#                        never loads two HDF5 libraries;
#   kimp_hdf5_serial     the serial flavour (Debian's libhdf5-dev, pkg-config hdf5-serial; its
#                        static archive when installed) for the lean `kimp`, which then loads
#                        no MPI; the parallel one when there is none of the same version.
# kimp_hdf5 links the one of the executable being linked: the serial one where that target's
# property KIMP_LEAN is true (cli/CMakeLists.txt), else the parallel one. kimp_hdf5_headers are
# the include directories to compile against: the serial headers when found (they need no mpi.h;
# the parallel library's API is the same, only extended), else the parallel ones with MPI's.
add_library(kimp_hdf5_parallel INTERFACE)
target_link_libraries(kimp_hdf5_parallel INTERFACE ${HDF5_C_LIBRARIES})

add_library(kimp_hdf5_headers INTERFACE)
add_library(kimp_hdf5_serial INTERFACE)
set(KIMP_HDF5_SERIAL_FOUND FALSE)
if(HDF5_IS_PARALLEL)
  find_package(PkgConfig QUIET)
  if(PkgConfig_FOUND)
    pkg_check_modules(KIMP_HDF5_SERIAL QUIET IMPORTED_TARGET hdf5-serial)
  endif()
  if(KIMP_HDF5_SERIAL_FOUND)
    set(serial_version "${KIMP_HDF5_SERIAL_VERSION}")
    if(NOT serial_version VERSION_EQUAL HDF5_VERSION)
      message(STATUS "kimp: serial HDF5 ${serial_version} differs from the parallel "
                     "${HDF5_VERSION}: the lean kimp links the parallel one (and MPI)")
      set(KIMP_HDF5_SERIAL_FOUND FALSE)
    endif()
  endif()
endif()
if(KIMP_HDF5_SERIAL_FOUND)
  # Its static archive where installed: the shared library loads libcurl and its ~25 libraries
  # (the read-only S3 driver), 20 ms of start-up on a loaded machine; the archive's objects need
  # only szip and zlib (the filters it registers).
  find_library(KIMP_HDF5_SERIAL_ARCHIVE NAMES libhdf5.a libhdf5_serial.a
               HINTS ${KIMP_HDF5_SERIAL_LIBRARY_DIRS} NO_DEFAULT_PATH)
  find_library(KIMP_SZIP_LIBRARY NAMES sz)
  find_package(ZLIB QUIET)
  if(KIMP_HDF5_SERIAL_ARCHIVE AND KIMP_SZIP_LIBRARY AND ZLIB_FOUND)
    message(STATUS "kimp: the lean kimp links the serial HDF5 ${serial_version} statically (no MPI)")
    target_link_libraries(kimp_hdf5_serial INTERFACE ${KIMP_HDF5_SERIAL_ARCHIVE}
                          ${KIMP_SZIP_LIBRARY} ZLIB::ZLIB ${CMAKE_DL_LIBS} m Threads::Threads)
  else()
    message(STATUS "kimp: the lean kimp links the serial HDF5 ${serial_version} (no MPI)")
    target_link_libraries(kimp_hdf5_serial INTERFACE PkgConfig::KIMP_HDF5_SERIAL)
  endif()
  target_include_directories(kimp_hdf5_headers SYSTEM INTERFACE ${KIMP_HDF5_SERIAL_INCLUDE_DIRS})
else()
  target_link_libraries(kimp_hdf5_serial INTERFACE ${HDF5_C_LIBRARIES})
  target_include_directories(kimp_hdf5_headers SYSTEM INTERFACE ${HDF5_C_INCLUDE_DIRS}
                                                                ${HDF5_INCLUDE_DIRS})
  target_compile_definitions(kimp_hdf5_headers INTERFACE ${HDF5_C_DEFINITIONS} ${HDF5_DEFINITIONS})
  if(HDF5_IS_PARALLEL)
    target_link_libraries(kimp_hdf5_headers INTERFACE MPI::MPI_C)
  endif()
endif()

add_library(kimp_hdf5 INTERFACE)
target_link_libraries(kimp_hdf5 INTERFACE kimp_hdf5_headers
  "$<IF:$<BOOL:$<TARGET_PROPERTY:KIMP_LEAN>>,kimp_hdf5_serial,kimp_hdf5_parallel>")
