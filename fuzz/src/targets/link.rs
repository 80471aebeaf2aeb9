//! The frame decoder: random bytes never panic and decode only to finite, canonical frames;
//! a valid frame with 1, 2 or 3 flipped bits is always rejected (CRC-16/CCITT detects every
//! error of fewer than 4 bits at this length).

use guidance_core::guidance::{Command, RateLimits};
use guidance_core::link::{CommandFrame, FRAME_LEN, Frame, LinkStatus, NavFrame, decode, encode};
use guidance_core::nav::NavState;
use rand::{Rng, RngExt};

use crate::hostile::value;

pub fn run<R: Rng>(rng: &mut R) -> Result<(), String> {
    random_bytes(rng)?;
    bit_flips(rng)
}

fn random_bytes<R: Rng>(rng: &mut R) -> Result<(), String> {
    let len = if rng.random_bool(0.9) {
        FRAME_LEN
    } else {
        rng.random_range(0..2 * FRAME_LEN)
    };
    let mut bytes: Vec<u8> = (0..len).map(|_| rng.random()).collect();
    if len == FRAME_LEN && rng.random_bool(0.5) {
        // Give the random body a valid sync word and checksum, so the decoder's later checks
        // (type, status, payload) are exercised too.
        bytes[0] = 0xA5;
        bytes[1] = 0x5A;
        bytes[2] = rng.random_range(0..5);
        bytes[3] = rng.random_range(0..10);
        let crc = guidance_core::link::crc16_ccitt(&bytes[..FRAME_LEN - 2]).to_le_bytes();
        bytes[FRAME_LEN - 2..].copy_from_slice(&crc);
    }
    let Ok(frame) = decode(&bytes) else {
        return Ok(());
    };
    let mut again = [0u8; FRAME_LEN];
    encode(&frame, &mut again)
        .map_err(|e| format!("decoded {frame:?} does not re-encode: {e:?}"))?;
    if again[..] != bytes[..] {
        return Err(format!("decoded {frame:?} is not canonical: {bytes:02x?}"));
    }
    Ok(())
}

fn frame<R: Rng>(rng: &mut R) -> Frame {
    let seq = rng.random();
    let mut f = || value(rng, -1e7, 1e7, 0.0);
    match seq % 3 {
        0 => Frame::Nav(NavFrame {
            seq,
            nav: NavState {
                time_s: f(),
                radius_m: f(),
                speed_m_s: f(),
                flight_path_angle_rad: f(),
                heading_rad: f(),
                latitude_rad: f(),
                longitude_rad: f(),
            },
            sensed: None,
        }),
        1 => Frame::Command(CommandFrame {
            seq,
            status: LinkStatus::Ok,
            tick_time_s: f(),
            command: Command {
                alpha_rad: f(),
                sigma_rad: f(),
            },
            ramp_start: Command {
                alpha_rad: f(),
                sigma_rad: f(),
            },
            rates: RateLimits {
                alpha_rad_s: f(),
                sigma_rad_s: f(),
            },
            reversals: 0,
            replans: 0,
        }),
        _ => Frame::End(seq),
    }
}

fn bit_flips<R: Rng>(rng: &mut R) -> Result<(), String> {
    let original = frame(rng);
    let mut bytes = [0u8; FRAME_LEN];
    encode(&original, &mut bytes).map_err(|e| format!("{original:?} does not encode: {e:?}"))?;
    if decode(&bytes) != Ok(original) {
        return Err(format!("{original:?} does not round-trip"));
    }
    let flips = rng.random_range(1..=3usize);
    let mut bits: Vec<usize> = Vec::new();
    while bits.len() < flips {
        let b = rng.random_range(0..FRAME_LEN * 8);
        if !bits.contains(&b) {
            bits.push(b);
        }
    }
    for &b in &bits {
        bytes[b / 8] ^= 1 << (b % 8);
    }
    match decode(&bytes) {
        Ok(f) => Err(format!("{flips} flipped bits {bits:?} accepted as {f:?}")),
        Err(_) => Ok(()),
    }
}
