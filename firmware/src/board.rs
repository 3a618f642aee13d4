//! The timer that counts guest instructions on each QEMU board (`build.rs`
//! sets `cfg(fw_board)` from the build target).
//!
//! Under `-icount shift=0` QEMU's virtual clock advances 1 ns per guest
//! instruction, so a timer clocked at F MHz counts one tick per 1000 / F
//! instructions, deterministically. [`INSNS_PER_TICK`] is that ratio as a
//! fraction (the nRF51's 16 MHz gives 62.5).

/// Guest instructions per timer tick, as `(numerator, denominator)`.
#[cfg(fw_board = "mps2-an386")]
pub const INSNS_PER_TICK: (u64, u64) = (40, 1); // CMSDK timer 0, 25 MHz
#[cfg(fw_board = "mps2-an505")]
pub const INSNS_PER_TICK: (u64, u64) = (50, 1); // SSE-200 timer 0, 20 MHz SYSCLK
#[cfg(fw_board = "microbit")]
pub const INSNS_PER_TICK: (u64, u64) = (125, 2); // nRF51 TIMER0, 16 MHz

/// Guest instructions in `ticks` timer ticks.
pub fn insns(ticks: u32) -> u64 {
    u64::from(ticks) * INSNS_PER_TICK.0 / INSNS_PER_TICK.1
}

/// CMSDK APB timer (MPS2 AN386 at 0x4000_0000; on the AN505 the IoTKit's
/// timer 0 is the same block, used at its Secure alias 0x5000_0000 since
/// the firmware runs Secure and leaves the PPCs at their reset state). A
/// 32-bit down-counter: CTRL +0, VALUE +4, RELOAD +8.
#[cfg(any(fw_board = "mps2-an386", fw_board = "mps2-an505"))]
mod regs {
    #[cfg(fw_board = "mps2-an386")]
    const BASE: usize = 0x4000_0000;
    #[cfg(fw_board = "mps2-an505")]
    const BASE: usize = 0x5000_0000;
    const CTRL: *mut u32 = BASE as *mut u32;
    const VALUE: *mut u32 = (BASE + 4) as *mut u32;
    const RELOAD: *mut u32 = (BASE + 8) as *mut u32;

    pub fn start() {
        // SAFETY: the timer registers of the board's memory map.
        unsafe {
            core::ptr::write_volatile(CTRL, 0);
            core::ptr::write_volatile(RELOAD, u32::MAX);
            core::ptr::write_volatile(VALUE, u32::MAX);
            core::ptr::write_volatile(CTRL, 1);
        }
    }

    pub fn now() -> u32 {
        // SAFETY: as in `start`. The timer counts down; report ticks up.
        u32::MAX - unsafe { core::ptr::read_volatile(VALUE) }
    }
}

/// nRF51 TIMER0 at 0x4000_8000: 16 MHz with prescaler 0, 32-bit up-counter,
/// read by triggering CAPTURE[0] and reading CC[0].
#[cfg(fw_board = "microbit")]
mod regs {
    const BASE: usize = 0x4000_8000;
    const TASKS_START: *mut u32 = BASE as *mut u32;
    const TASKS_STOP: *mut u32 = (BASE + 0x004) as *mut u32;
    const TASKS_CLEAR: *mut u32 = (BASE + 0x00C) as *mut u32;
    const TASKS_CAPTURE0: *mut u32 = (BASE + 0x040) as *mut u32;
    const MODE: *mut u32 = (BASE + 0x504) as *mut u32;
    const BITMODE: *mut u32 = (BASE + 0x508) as *mut u32;
    const PRESCALER: *mut u32 = (BASE + 0x510) as *mut u32;
    const CC0: *mut u32 = (BASE + 0x540) as *mut u32;

    pub fn start() {
        // SAFETY: the TIMER0 registers of the nRF51 memory map.
        unsafe {
            core::ptr::write_volatile(TASKS_STOP, 1);
            core::ptr::write_volatile(MODE, 0); // timer, not counter
            core::ptr::write_volatile(BITMODE, 3); // 32 bits
            core::ptr::write_volatile(PRESCALER, 0); // 16 MHz
            core::ptr::write_volatile(TASKS_CLEAR, 1);
            core::ptr::write_volatile(TASKS_START, 1);
        }
    }

    pub fn now() -> u32 {
        // SAFETY: as in `start`.
        unsafe {
            core::ptr::write_volatile(TASKS_CAPTURE0, 1);
            core::ptr::read_volatile(CC0)
        }
    }
}

/// Restarts the timer from zero.
pub fn timer_start() {
    regs::start();
}

/// Ticks since [`timer_start`] (counting up; wraps after 2^32).
pub fn timer_now() -> u32 {
    regs::now()
}
