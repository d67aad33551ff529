# One INTERFACE target every weft target links: no fused multiply-add, IEEE division and square root,
# no flush-to-zero, never fast-math. With it, + - * / and sqrt round the same on the host and the GPU.
add_library(weft_fp_policy INTERFACE)
add_library(weft::fp_policy ALIAS weft_fp_policy)
set_target_properties(weft_fp_policy PROPERTIES EXPORT_NAME fp_policy)  # installed with weft::solver
if("CUDA" IN_LIST Kokkos_DEVICES)
  # nvcc_wrapper hands -f options to the host compiler.
  target_compile_options(weft_fp_policy INTERFACE
    --fmad=false --prec-div=true --prec-sqrt=true --ftz=false -ffp-contract=off -fno-fast-math)
else()
  target_compile_options(weft_fp_policy INTERFACE -ffp-contract=off -fno-fast-math)
endif()
