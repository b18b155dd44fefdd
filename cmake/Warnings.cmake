add_library(rtrt_warnings INTERFACE)
target_compile_options(rtrt_warnings INTERFACE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wno-missing-field-initializers>
    $<$<COMPILE_LANGUAGE:CUDA>:-Xcompiler=-Wall --expt-relaxed-constexpr -diag-suppress=20012>)

# Host code for this machine's vector units (AVX2 on the development and CI machines). Turn off
# for binaries that must run on other x86-64 CPUs.
option(RTRT_NATIVE "Compile host code with -march=native" ON)
if(RTRT_NATIVE)
    target_compile_options(rtrt_warnings INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-march=native>)
endif()
