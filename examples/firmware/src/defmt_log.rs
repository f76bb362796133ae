//! A `defmt` global logger for the firmware's check (feature `defmt`): frames encoded as
//! defmt encodes them for a probe (rzCOBS), kept in RAM and printed once as a hex
//! `defmt` record over semihosting, so the host check decodes them with the ELF's
//! interned strings (`defmt-decoder`) — kinegen's `defmt::Format` impls exercised on
//! the target, end to end. A board would use `defmt-rtt` instead; the frames are the
//! same.

use core::cell::UnsafeCell;
use core::fmt::Write;
use core::sync::atomic::{AtomicBool, Ordering};

use cortex_m_semihosting::hio::HostStream;

/// Bytes of frames kept (the firmware's log takes about 2 KB).
const CAPACITY: usize = 8 * 1024;

/// The encoded frames so far.
struct Frames {
    bytes: [u8; CAPACITY],
    len: usize,
    /// Frames did not fit: the record says so rather than print a cut stream.
    overflow: bool,
}

impl Frames {
    fn append(&mut self, bytes: &[u8]) {
        match self.bytes.get_mut(self.len..self.len + bytes.len()) {
            Some(dst) => {
                dst.copy_from_slice(bytes);
                self.len += bytes.len();
            }
            None => self.overflow = true,
        }
    }
}

/// A value only the holder of [`TAKEN`] touches.
struct Owned<T>(UnsafeCell<T>);

// SAFETY: one core, and no interrupt handler logs: `TAKEN` (set by `acquire`, cleared by
// `release`) makes every access one at a time.
unsafe impl<T> Sync for Owned<T> {}

static ENCODER: Owned<defmt::Encoder> = Owned(UnsafeCell::new(defmt::Encoder::new()));
static FRAMES: Owned<Frames> = Owned(UnsafeCell::new(Frames {
    bytes: [0; CAPACITY],
    len: 0,
    overflow: false,
}));
static TAKEN: AtomicBool = AtomicBool::new(false);

/// `f` on the encoder and the frames, for the holder of [`TAKEN`].
///
/// # Safety
/// Only between `acquire` and `release`, or with no logging under way.
unsafe fn with<R>(f: impl FnOnce(&mut defmt::Encoder, &mut Frames) -> R) -> R {
    // SAFETY: two distinct statics, each borrowed once, by the caller's contract alone.
    unsafe { f(&mut *ENCODER.0.get(), &mut *FRAMES.0.get()) }
}

#[defmt::global_logger]
struct Logger;

// SAFETY: `acquire` refuses to nest (a nested log would interleave two frames); defmt
// calls `write`, `flush` and `release` only between `acquire` and `release`.
unsafe impl defmt::Logger for Logger {
    fn acquire() {
        if TAKEN.swap(true, Ordering::Acquire) {
            panic!("defmt logger acquired twice");
        }
        // SAFETY: taken just above.
        unsafe { with(|e, frames| e.start_frame(|b| frames.append(b))) }
    }

    unsafe fn flush() {}

    unsafe fn release() {
        // SAFETY: defmt's contract: after `acquire`.
        unsafe { with(|e, frames| e.end_frame(|b| frames.append(b))) };
        TAKEN.store(false, Ordering::Release);
    }

    unsafe fn write(bytes: &[u8]) {
        // SAFETY: defmt's contract: after `acquire`.
        unsafe { with(|e, frames| e.write(bytes, |b| frames.append(b))) }
    }
}

/// Prints the frames logged so far as one record, `defmt <hex bytes>` (or `error defmt
/// frames over N bytes`), and forgets them.
pub fn print(out: &mut HostStream) {
    if TAKEN.load(Ordering::Acquire) {
        let _ = writeln!(out, "error defmt logger still taken");
        return;
    }
    // SAFETY: no log is under way (checked above; one core, no interrupts log).
    unsafe {
        with(|_, frames| {
            if frames.overflow {
                let _ = writeln!(out, "error defmt frames over {CAPACITY} bytes");
            } else {
                let _ = write!(out, "defmt ");
                for b in &frames.bytes[..frames.len] {
                    let _ = write!(out, "{b:02x}");
                }
                let _ = writeln!(out);
            }
            frames.len = 0;
        })
    }
}
