# CMake toolchain file: riscv64-unknown-elf-gcc for RV32IMAC with the
# soft-float ABI and picolibc (semihosting crt0 and stdio), for QEMU's virt
# machine; find_package(aaglsd) then picks riscv32imc-unknown-none-elf.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR riscv32)
set(CMAKE_C_COMPILER riscv64-unknown-elf-gcc)
set(CMAKE_C_FLAGS_INIT "-march=rv32imac -mabi=ilp32 --specs=picolibc.specs --oslib=semihost --crt0=semihost")
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
