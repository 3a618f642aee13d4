# find_package(aaglsd) for the aaglsd C distributable (ffi/dist.sh).
#
# Defines the imported target aaglsd::aaglsd: the header directory and the
# archive lib/<rust-target>/libaaglsd.a that matches the C compiler's core
# and float ABI, read from its predefined macros (the compiler and
# CMAKE_C_FLAGS, e.g. -mcpu=cortex-m4 -mfloat-abi=hard):
#
#   Arm M profile, hard-float ABI (__ARM_PCS_VFP):
#     ARMv8-M / v8.1-M Mainline (Cortex-M33, M35P, M55, M85)
#                                                     thumbv8m.main-none-eabihf
#     ARMv7E-M (Cortex-M4F, M7)                       thumbv7em-none-eabihf
#   Arm M profile, soft or softfp ABI:
#     with the DSP extension (Cortex-M4, M7, M33, ...) thumbv7em-none-eabi
#     otherwise (Cortex-M0, M0+, M1, M3, M23)          thumbv6m-none-eabi
#   RISC-V RV32 with the C extension, soft-float ABI   riscv32imc-unknown-none-elf
#
# Set AAGLSD_RUST_TARGET before find_package to choose an archive yourself.
# aaglsd::aaglsd also adds -Wl,--gc-sections to the link (the archive's
# unused code and the parts of compiler_builtins nothing calls are then
# dropped); set AAGLSD_GC_SECTIONS to OFF to leave the link options alone.
# Sets aaglsd_RUST_TARGET and aaglsd_VERSION.

cmake_minimum_required(VERSION 3.13)
set(aaglsd_VERSION @AAGLSD_VERSION@)
get_filename_component(_aaglsd_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)

function(_aaglsd_pick_target out)
  if(NOT CMAKE_C_COMPILER)
    set(${out} "" PARENT_SCOPE)
    set(_aaglsd_why "the C language is not enabled (project(... C) before find_package(aaglsd))" PARENT_SCOPE)
    return()
  endif()
  separate_arguments(_flags UNIX_COMMAND "${CMAKE_C_FLAGS}")
  set(_empty "${CMAKE_CURRENT_BINARY_DIR}/aaglsd_probe_empty.c")
  file(WRITE "${_empty}" "")
  execute_process(
    COMMAND "${CMAKE_C_COMPILER}" ${_flags} -dM -E "${_empty}"
    OUTPUT_VARIABLE _macros ERROR_VARIABLE _err RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    set(${out} "" PARENT_SCOPE)
    set(_aaglsd_why "`${CMAKE_C_COMPILER} -dM -E` failed: ${_err}" PARENT_SCOPE)
    return()
  endif()
  macro(_has name)
    string(REGEX MATCH "#define ${name}( |\n)" _m "${_macros}")
  endmacro()
  macro(_value name)
    string(REGEX MATCH "#define ${name} ([^\n]*)" _m "${_macros}")
    set(_v "${CMAKE_MATCH_1}")
  endmacro()
  set(_t "")
  _value(__ARM_ARCH_PROFILE)
  if(_v STREQUAL "77" OR _v STREQUAL "'M'")
    _value(__ARM_ARCH)
    set(_arch "${_v}")
    _has(__ARM_PCS_VFP)
    set(_hard "${_m}")
    _has(__ARM_FEATURE_DSP)
    set(_dsp "${_m}")
    _has(__ARM_ARCH_8M_MAIN__)
    set(_v8main "${_m}")
    if(NOT _v8main)
      _has(__ARM_ARCH_8_1M_MAIN__)
      set(_v8main "${_m}")
    endif()
    _has(__ARM_ARCH_7EM__)
    set(_v7em "${_m}")
    if(_hard)
      if(_v8main)
        set(_t thumbv8m.main-none-eabihf)
      elseif(_v7em)
        set(_t thumbv7em-none-eabihf)
      else()
        set(_aaglsd_why "a hard-float ABI on an M-profile core that is neither ARMv7E-M nor ARMv8-M Mainline" PARENT_SCOPE)
      endif()
    elseif(_dsp AND _arch GREATER_EQUAL 7)
      set(_t thumbv7em-none-eabi)
    else()
      set(_t thumbv6m-none-eabi)
    endif()
  else()
    _has(__riscv)
    if(_m)
      _value(__riscv_xlen)
      set(_xlen "${_v}")
      _has(__riscv_compressed)
      set(_rvc "${_m}")
      _has(__riscv_float_abi_soft)
      set(_soft "${_m}")
      _has(__riscv_32e)
      set(_rv32e "${_m}")
      if(_xlen STREQUAL "32" AND _rvc AND _soft AND NOT _rv32e)
        set(_t riscv32imc-unknown-none-elf)
      else()
        set(_aaglsd_why "a RISC-V target other than RV32 with the C extension and the soft-float ABI (ilp32)" PARENT_SCOPE)
      endif()
    else()
      set(_aaglsd_why "neither an Arm M-profile nor a RISC-V compiler (the archives are for bare-metal targets)" PARENT_SCOPE)
    endif()
  endif()
  set(${out} "${_t}" PARENT_SCOPE)
endfunction()

set(_aaglsd_why "")
if(AAGLSD_RUST_TARGET)
  set(aaglsd_RUST_TARGET "${AAGLSD_RUST_TARGET}")
else()
  _aaglsd_pick_target(aaglsd_RUST_TARGET)
endif()
set(_aaglsd_lib "${_aaglsd_prefix}/lib/${aaglsd_RUST_TARGET}/libaaglsd.a")
if(NOT aaglsd_RUST_TARGET)
  set(aaglsd_FOUND FALSE)
  set(aaglsd_NOT_FOUND_MESSAGE "aaglsd: no archive for ${CMAKE_C_COMPILER} ${CMAKE_C_FLAGS}: ${_aaglsd_why}. Set AAGLSD_RUST_TARGET to one of the folders in ${_aaglsd_prefix}/lib.")
  return()
endif()
if(NOT EXISTS "${_aaglsd_lib}")
  set(aaglsd_FOUND FALSE)
  set(aaglsd_NOT_FOUND_MESSAGE "aaglsd: ${_aaglsd_lib} is missing (this distributable was built without ${aaglsd_RUST_TARGET}: ffi/dist.sh with AAGLSD_DIST_TARGETS).")
  return()
endif()

if(NOT TARGET aaglsd::aaglsd)
  add_library(aaglsd::aaglsd STATIC IMPORTED)
  set_target_properties(aaglsd::aaglsd PROPERTIES
    IMPORTED_LOCATION "${_aaglsd_lib}"
    IMPORTED_LINK_INTERFACE_LANGUAGES C
    INTERFACE_INCLUDE_DIRECTORIES "${_aaglsd_prefix}/include")
  if(NOT DEFINED AAGLSD_GC_SECTIONS OR AAGLSD_GC_SECTIONS)
    set_property(TARGET aaglsd::aaglsd PROPERTY INTERFACE_LINK_OPTIONS "LINKER:--gc-sections")
  endif()
endif()
if(NOT aaglsd_FIND_QUIETLY)
  message(STATUS "aaglsd ${aaglsd_VERSION}: ${aaglsd_RUST_TARGET} (${_aaglsd_lib})")
endif()
set(aaglsd_FOUND TRUE)
