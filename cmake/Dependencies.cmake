# Every dependency comes from Debian's packages (scripts/setup.sh installs them).
find_package(Eigen3 3.4 REQUIRED CONFIG)
find_package(orocos_kdl REQUIRED CONFIG)
find_package(urdfdom REQUIRED CONFIG)
# tinyxml2 checks robot files before urdfdom (and its TinyXML 2.6) sees them (issue #28).
find_package(tinyxml2 REQUIRED CONFIG)
find_package(fcl REQUIRED CONFIG)
# Collision meshes of URDFs (STL, OBJ, COLLADA) and their convex hulls.
find_package(assimp REQUIRED CONFIG)
find_package(Qhull REQUIRED CONFIG)
find_package(NLopt REQUIRED CONFIG)
find_package(yaml-cpp REQUIRED CONFIG)
find_package(nlohmann_json 3.11 REQUIRED CONFIG)
find_package(CLI11 REQUIRED CONFIG)
# MuJoCo's exported target names libqhull's include folder, so libqhull-dev must be installed too.
find_package(mujoco REQUIRED CONFIG)
find_package(PkgConfig REQUIRED)
# Debian's Ipopt 3.11 ships no CMake config, only pkg-config.
pkg_check_modules(IPOPT REQUIRED IMPORTED_TARGET GLOBAL ipopt)
# CLP (coinor-libclp-dev), the second QP reference: optional, pkg-config only like Ipopt.
pkg_check_modules(CLP IMPORTED_TARGET GLOBAL clp)
set(STAIRPLAN_HAS_CLP ${CLP_FOUND})
if(STAIRPLAN_BUILD_TESTS)
  find_package(Catch2 2 REQUIRED CONFIG)
  include(Catch)
endif()
if(STAIRPLAN_BUILD_BENCH)
  find_package(benchmark REQUIRED CONFIG)
endif()
# Optional: `mpirun -np N stairplan sweep` (Open MPI, libopenmpi-dev); without it sweeps use threads and shards.
find_package(MPI COMPONENTS CXX QUIET)
