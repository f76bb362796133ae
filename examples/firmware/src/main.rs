//! UR5 forward kinematics, Jacobian and determinant in f64 and f32, and the closed-form
//! inverse kinematics (all solutions, f64 and f32), and the Kinova Jaco's general 6R
//! inverse kinematics (f64) on a Cortex-M4F, with the stack each `ik` takes, reported
//! over semihosting (QEMU `mps2-an386`; see README.md).
//!
//! Output, one record per line, fields separated by one space, numbers in Rust's `{:?}`
//! form (shortest text that reads back to the same float):
//!
//! ```text
//! kinegen-firmware v4
//! cpacr 0x00f00000                      FPU access bits (CP10/CP11 full access = 0x00f00000)
//! <f64|f32> <case> q   <6 joint values>
//! <f64|f32> <case> fk  <16 entries of T, row-major>
//! <f64|f32> <case> jac <36 entries of J, row-major>
//! <f64|f32> <case> det <det J>
//! <f64|f32> <case> ik <count> then per solution: <1 if exact else 0> <6 joint values>
//!                                       (every solution of `ik(fk(q))`; f32: solved in f64)
//! defmt <hex bytes>                     (feature `defmt`: the same solutions as defmt
//!                                       frames, `ur5 <f64|f32> <case> <IkSolutions>`)
//! f64 <case> jaco-q  <6 joint values>    (the Jaco's configurations, `JACO_CONFIGS`)
//! f64 <case> jaco-ik <count> then per solution as above (general 6R, every solution)
//! stack <function> <bytes>              (stack below the caller's, by painting)
//! end
//! ```
//!
//! then a semihosting exit with status 0. A panic or a HardFault prints `error ...` and
//! exits with status 1, so QEMU never keeps running.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(all(target_os = "none", feature = "defmt"))]
mod defmt_log;

#[cfg(target_os = "none")]
mod firmware {
    use core::fmt::Write;
    use core::hint::black_box;

    use cortex_m_rt::{entry, exception, ExceptionFrame};
    use cortex_m_semihosting::{debug, hio};
    use kinegen_firmware::{to_f32, Ur5F32, CONFIGS, HEADER, JACO_CONFIGS, TRAILER};
    use kinegen_robots::{KinovaJaco, Ur5};

    // One function per generated method, never inlined, with plain symbol names: their
    // sizes in the ELF are the flash the generated code takes (README.md, "Flash size").

    /// `Ur5::fk` (f64, software floating point on the M4F).
    #[no_mangle]
    #[inline(never)]
    pub fn ur5_fk_f64(r: &Ur5, q: &[f64; 6]) -> [[f64; 4]; 4] {
        r.fk(q)
    }
    /// `Ur5::jacobian` (f64).
    #[no_mangle]
    #[inline(never)]
    pub fn ur5_jacobian_f64(r: &Ur5, q: &[f64; 6]) -> [[f64; 6]; 6] {
        r.jacobian(q)
    }
    /// `Ur5::jacobian_det` (f64).
    #[no_mangle]
    #[inline(never)]
    pub fn ur5_jacobian_det_f64(r: &Ur5, q: &[f64; 6]) -> f64 {
        r.jacobian_det(q)
    }
    /// `Ur5::ik` (f64): every closed-form solution of a pose.
    #[no_mangle]
    #[inline(never)]
    pub fn ur5_ik_f64(r: &Ur5, pose: &[[f64; 4]; 4]) -> kinegen::ik::IkSolutions<6, 8> {
        r.ik(pose)
    }
    /// `Ur5F32::ik` (f32 pose and joint values, solved in f64: soft-float).
    #[no_mangle]
    #[inline(never)]
    pub fn ur5_ik_f32(r: &Ur5F32, pose: &[[f32; 4]; 4]) -> kinegen::ik::IkSolutions<6, 8, f32> {
        r.ik(pose)
    }
    /// `KinovaJaco::ik` (f64): the general 6R, every solution.
    #[no_mangle]
    #[inline(never)]
    pub fn jaco_ik_f64(r: &KinovaJaco, pose: &[[f64; 4]; 4]) -> kinegen::ik::IkSolutions<6, 16> {
        r.ik(pose)
    }
    /// `KinovaJaco::fk` (f64).
    #[no_mangle]
    #[inline(never)]
    pub fn jaco_fk_f64(r: &KinovaJaco, q: &[f64; 6]) -> [[f64; 4]; 4] {
        r.fk(q)
    }
    /// `Ur5F32::fk` (f32, on the FPU).
    #[no_mangle]
    #[inline(never)]
    pub fn ur5_fk_f32(r: &Ur5F32, q: &[f32; 6]) -> [[f32; 4]; 4] {
        r.fk(q)
    }
    /// `Ur5F32::jacobian` (f32).
    #[no_mangle]
    #[inline(never)]
    pub fn ur5_jacobian_f32(r: &Ur5F32, q: &[f32; 6]) -> [[f32; 6]; 6] {
        r.jacobian(q)
    }
    /// `Ur5F32::jacobian_det` (f32).
    #[no_mangle]
    #[inline(never)]
    pub fn ur5_jacobian_det_f32(r: &Ur5F32, q: &[f32; 6]) -> f32 {
        r.jacobian_det(q)
    }

    /// Ends the QEMU run with `status` (semihosting `SYS_EXIT`); on a debug probe that
    /// ignores it, waits here.
    fn exit(status: debug::ExitStatus) -> ! {
        debug::exit(status);
        loop {
            core::hint::spin_loop();
        }
    }

    /// Bytes painted below the stack pointer before a call: more than any `ik` takes.
    const PAINT: usize = 512 * 1024;
    const PATTERN: u32 = 0x5aa5_c33c;

    /// `f()` and the bytes of stack it used below this function's frame: the words below
    /// the stack pointer are painted first, and after the call the lowest one overwritten
    /// marks the deepest point (`PAINT` if all were: more than measured). The result itself
    /// lives in this frame, not counted. No interrupts run here, so nothing else writes
    /// below the stack pointer.
    #[inline(never)]
    fn stack_use<R>(f: impl FnOnce() -> R) -> (R, usize) {
        let sp: usize;
        // SAFETY: reads the stack pointer into a register; no memory is touched.
        unsafe { core::arch::asm!("mov {}, sp", out(reg) sp, options(nomem, nostack)) };
        let bottom = (sp - PAINT) & !3;
        let mut a = bottom;
        while a < sp - 16 {
            // SAFETY: the stack's free part (cortex-m-rt puts the stack at the top of the
            // 4 MB RAM; `PAINT` is far above .data/.bss), word-aligned, used by nobody now.
            unsafe { core::ptr::write_volatile(a as *mut u32, PATTERN) };
            a += 4;
        }
        let r = black_box(f());
        let mut lowest = bottom;
        // SAFETY: the same words, read back.
        while lowest < sp - 16
            && unsafe { core::ptr::read_volatile(lowest as *const u32) } == PATTERN
        {
            lowest += 4;
        }
        (r, sp - lowest)
    }

    /// `name` followed by the values, one line.
    fn record<T: core::fmt::Debug>(
        out: &mut hio::HostStream,
        scalar: &str,
        case: usize,
        name: &str,
        values: impl IntoIterator<Item = T>,
    ) {
        let _ = write!(out, "{scalar} {case} {name}");
        for v in values {
            let _ = write!(out, " {v:?}");
        }
        let _ = writeln!(out);
    }

    /// The solutions as the `ik` record lists them: the count, then per solution the
    /// exact flag and the joint values.
    fn ik_record<T: Copy + Default + From<u8>, const K: usize>(
        s: &kinegen::ik::IkSolutions<6, K, T>,
    ) -> impl Iterator<Item = T> + '_ {
        core::iter::once(T::from(s.len() as u8)).chain(
            s.iter()
                .flat_map(|b| core::iter::once(T::from(u8::from(b.exact))).chain(b.q)),
        )
    }

    #[entry]
    fn main() -> ! {
        let Ok(mut out) = hio::hstdout() else {
            exit(debug::EXIT_FAILURE);
        };
        let _ = writeln!(out, "{HEADER}");
        // Coprocessor Access Control Register: cortex-m-rt's reset code grants CP10/CP11
        // (the FPU) full access on eabihf targets; without it the first f32 instruction
        // would fault.
        // SAFETY: CPACR is an always-readable System Control Block register.
        let cpacr = unsafe { core::ptr::read_volatile(0xE000_ED88 as *const u32) };
        let _ = writeln!(out, "cpacr {cpacr:#010x}");

        // black_box: the configurations are constants; keep the compiler from
        // evaluating the kinematics at compile time.
        let (r64, r32) = (black_box(Ur5::default()), black_box(Ur5F32::default()));
        for (case, q) in CONFIGS.iter().enumerate() {
            let q = black_box(*q);
            record(&mut out, "f64", case, "q", q);
            record(
                &mut out,
                "f64",
                case,
                "fk",
                ur5_fk_f64(&r64, &q).into_iter().flatten(),
            );
            record(
                &mut out,
                "f64",
                case,
                "jac",
                ur5_jacobian_f64(&r64, &q).into_iter().flatten(),
            );
            record(
                &mut out,
                "f64",
                case,
                "det",
                [ur5_jacobian_det_f64(&r64, &q)],
            );

            let pose = black_box(ur5_fk_f64(&r64, &q));
            record(
                &mut out,
                "f64",
                case,
                "ik",
                ik_record(&ur5_ik_f64(&r64, &pose)),
            );

            let q = black_box(to_f32(&q));
            record(&mut out, "f32", case, "q", q);
            record(
                &mut out,
                "f32",
                case,
                "fk",
                ur5_fk_f32(&r32, &q).into_iter().flatten(),
            );
            record(
                &mut out,
                "f32",
                case,
                "jac",
                ur5_jacobian_f32(&r32, &q).into_iter().flatten(),
            );
            record(
                &mut out,
                "f32",
                case,
                "det",
                [ur5_jacobian_det_f32(&r32, &q)],
            );
            let pose = black_box(ur5_fk_f32(&r32, &q));
            record(
                &mut out,
                "f32",
                case,
                "ik",
                ik_record(&ur5_ik_f32(&r32, &pose)),
            );
        }
        // With `defmt`: the same solutions logged through kinegen's `defmt::Format` (the
        // host decodes them and compares with the records above).
        #[cfg(feature = "defmt")]
        {
            for (case, q) in CONFIGS.iter().enumerate() {
                let pose = black_box(ur5_fk_f64(&r64, q));
                defmt::println!("ur5 f64 {=usize} {}", case, ur5_ik_f64(&r64, &pose));
                let q = to_f32(q);
                let pose = black_box(ur5_fk_f32(&r32, &q));
                defmt::println!("ur5 f32 {=usize} {}", case, ur5_ik_f32(&r32, &pose));
            }
            crate::defmt_log::print(&mut out);
        }
        // The general 6R on the Jaco: every solution, and the stack it takes.
        let jaco = black_box(KinovaJaco::default());
        let mut jaco_stack = 0;
        for (case, q) in JACO_CONFIGS.iter().enumerate() {
            let q = black_box(*q);
            record(&mut out, "f64", case, "jaco-q", q);
            let pose = black_box(jaco_fk_f64(&jaco, &q));
            let (ik, used) = stack_use(|| jaco_ik_f64(&jaco, &pose));
            jaco_stack = jaco_stack.max(used);
            record(&mut out, "f64", case, "jaco-ik", ik_record(&ik));
        }
        // The UR5's `ik` for comparison (the same poses as above).
        let mut ur5_stack = 0;
        for q in &CONFIGS {
            let pose = black_box(ur5_fk_f64(&r64, q));
            ur5_stack = ur5_stack.max(stack_use(|| ur5_ik_f64(&r64, &pose)).1);
        }
        let _ = writeln!(out, "stack jaco_ik_f64 {jaco_stack}");
        let _ = writeln!(out, "stack ur5_ik_f64 {ur5_stack}");
        let _ = writeln!(out, "{TRAILER}");
        exit(debug::EXIT_SUCCESS)
    }

    #[exception]
    unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
        if let Ok(mut out) = hio::hstdout() {
            let _ = writeln!(out, "error HardFault at pc {:#010x}", frame.pc());
        }
        exit(debug::EXIT_FAILURE)
    }

    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        if let Ok(mut out) = hio::hstdout() {
            let _ = writeln!(out, "error {info}");
        }
        exit(debug::EXIT_FAILURE)
    }
}

/// The firmware binary is for the microcontroller only.
#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "the `firmware` binary runs on thumbv7em-none-eabihf (see README.md); \
         on the host, run `check`"
    );
    std::process::exit(2);
}
