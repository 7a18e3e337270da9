# Header-only Debian packages (Eigen, Catch2, CLI11, nlohmann-json, stb) live under /usr/include.
# A cross compiler must not see /usr/include (host glibc headers), so each package's own
# directory is exposed through a small symlink farm in the build tree.
set(DPCR_HOST_HEADERS_DIR ${CMAKE_BINARY_DIR}/host_headers)
file(MAKE_DIRECTORY ${DPCR_HOST_HEADERS_DIR})

find_path(DPCR_EIGEN_DIR Eigen/Core PATHS /usr/include/eigen3 NO_CMAKE_FIND_ROOT_PATH REQUIRED)
add_library(dpcr_eigen INTERFACE)
target_include_directories(dpcr_eigen SYSTEM INTERFACE ${DPCR_EIGEN_DIR})
# Fixed-size matrices only in the core: any Eigen heap allocation is a bug (asserts at run time).
target_compile_definitions(dpcr_eigen INTERFACE EIGEN_NO_MALLOC EIGEN_MPL2_ONLY)

foreach(pkg catch2 CLI nlohmann stb)
  if(EXISTS /usr/include/${pkg} AND NOT EXISTS ${DPCR_HOST_HEADERS_DIR}/${pkg})
    file(CREATE_LINK /usr/include/${pkg} ${DPCR_HOST_HEADERS_DIR}/${pkg} SYMBOLIC)
  endif()
endforeach()
add_library(dpcr_host_headers INTERFACE)
target_include_directories(dpcr_host_headers SYSTEM INTERFACE ${DPCR_HOST_HEADERS_DIR})
