# Every dependency is a Debian package (../shared/BUILD_NOTES.md says how each one behaves).
find_package(glm REQUIRED)
find_package(TBB REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(ZLIB REQUIRED)
# xxHash (libxxhash-dev) is used header-only (XXH_INLINE_ALL): no library to link.
find_path(XXHASH_INCLUDE_DIR xxhash.h REQUIRED)
find_package(PkgConfig REQUIRED)
if(RTRT_WITH_OIIO)
    # Debian's OpenImageIOConfig.cmake names a missing opencv4 include dir; pkg-config works.
    pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
endif()
if(RTRT_BUILD_TESTS)
    find_package(GTest REQUIRED)
endif()
