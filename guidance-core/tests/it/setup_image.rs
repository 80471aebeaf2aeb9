//! Set-up protocol v2 ([`guidance_core::setup::image`]): a [`StackConfig`] survives its image
//! bit for bit, the firmware's scalars fly exactly the stack the host builds in them, every
//! refusal is typed, and the chunked upload reassembles the image.

use guidance_core::lateral::{CorridorAxis, TerminalLateral};
use guidance_core::replan::{LiftSchedule, RangeTarget};
use guidance_core::setup::image::{
    CHUNK_BYTES, IMAGE_VERSION, ImageError, ImageReceiver, chunks, crc32, decode, encode,
    image_capacity,
};
use guidance_core::stack::{FlightStack, Layer, Layers, StackConfig};
use guidance_core::{Fixed, NavState};

use crate::stack::{full, samples, sensed};
use crate::vinh_replan::normalizer;

const CAP: usize = image_capacity(16);

/// [`full`] with every optional part on: lift schedule, start energy, E-hat corridor,
/// terminal law, a Hermite table.
fn everything() -> StackConfig<f64> {
    let mut c = full();
    c.profile.interpolation =
        guidance_core::interp::Interpolation::CardinalHermite { tension: 0.25 };
    if let Some(r) = c.replan.as_mut() {
        r.lift_schedule = Some(LiftSchedule::linear(7000.0, 1.2, 3000.0, 0.8));
        r.start_normalized_energy = Some(0.9);
        r.numerical_rotation = true;
        r.bank_shape = true;
        r.steps_per_tick = 3;
    }
    if let Some(l) = c.lateral.as_mut() {
        l.corridor.axis = CorridorAxis::NormalizedEnergy(normalizer());
        l.corridor.x_high = 0.9;
        l.corridor.x_low = 0.2;
        l.terminal = Some(TerminalLateral {
            start_angle_rad: 0.05,
            tolerance_rad: 1e-4,
            reversal_lead_s: 5.7,
        });
    }
    c
}

fn image(c: &StackConfig<f64>) -> Vec<u8> {
    let mut b = [0u8; CAP];
    let n = encode(c, &mut b).unwrap();
    b[..n].to_vec()
}

fn reseal(b: &mut [u8]) {
    let n = b.len();
    let crc = crc32(&b[..n - 4]);
    b[n - 4..].copy_from_slice(&crc.to_le_bytes());
}

#[test]
fn every_layer_round_trips_bit_for_bit() {
    for c in [full(), everything(), full().masked(Layers::PROFILE)] {
        let img = image(&c);
        assert!(img.len() <= CAP);
        let back = decode::<f64, 16, f64>(&img, Layers::ALL).unwrap();
        assert_eq!(back, c);
        // A flown range angle as the target.
        let mut r = c.masked(Layers {
            lateral: false,
            ..Layers::ALL
        });
        if r.replan.is_some() {
            r.target = Some(RangeTarget::FlownRangeAngle { total_rad: 0.3 });
            assert_eq!(decode::<f64, 16, f64>(&image(&r), Layers::ALL).unwrap(), r);
        }
    }
}

/// What the firmware flies (f32, or the M3's fixed-point tick with f32 layers) is what the
/// host flies with the same decode: the image is the one source of both.
#[test]
fn decoded_stacks_fly_in_the_firmware_scalars() {
    let img = image(&everything());
    let c32 = decode::<f32, 16, f32>(&img, Layers::ALL).unwrap();
    let mut s32 = FlightStack::new(&c32).unwrap();
    let cfx = decode::<Fixed, 16, f32>(&img, Layers::ALL).unwrap();
    let mut sfx = FlightStack::new(&cfx).unwrap();
    let mut s64 = FlightStack::new(&everything()).unwrap();
    for n in samples() {
        let m = sensed(&n);
        let o64 = s64.tick(&n, Some(&m)).unwrap();
        let n32 = NavState {
            time_s: n.time_s as f32,
            radius_m: n.radius_m as f32,
            speed_m_s: n.speed_m_s as f32,
            flight_path_angle_rad: n.flight_path_angle_rad as f32,
            heading_rad: n.heading_rad as f32,
            latitude_rad: n.latitude_rad as f32,
            longitude_rad: n.longitude_rad as f32,
        };
        let m32 = guidance_core::estimate::SensedAero {
            lift_m_s2: m.lift_m_s2 as f32,
            drag_m_s2: m.drag_m_s2 as f32,
        };
        let o32 = s32.tick(&n32, Some(&m32)).unwrap();
        let nfx = NavState {
            time_s: <Fixed as guidance_core::Scalar>::from_f64(n.time_s),
            radius_m: <Fixed as guidance_core::Scalar>::from_f64(n.radius_m),
            speed_m_s: <Fixed as guidance_core::Scalar>::from_f64(n.speed_m_s),
            flight_path_angle_rad: <Fixed as guidance_core::Scalar>::from_f64(
                n.flight_path_angle_rad,
            ),
            heading_rad: <Fixed as guidance_core::Scalar>::from_f64(n.heading_rad),
            latitude_rad: <Fixed as guidance_core::Scalar>::from_f64(n.latitude_rad),
            longitude_rad: <Fixed as guidance_core::Scalar>::from_f64(n.longitude_rad),
        };
        sfx.tick(&nfx, Some(&m32)).unwrap();
        assert_eq!(o32.ticked, o64.ticked);
        // f32 against f64: the same guidance within its rounding (a bank of the same sign).
        assert_eq!(
            o32.command.sigma_rad.signum(),
            o64.command.sigma_rad.signum() as f32,
            "t {}",
            n.time_s
        );
    }
    assert_eq!(s32.reversals(), s64.reversals());
    assert_eq!(sfx.reversals(), s64.reversals());
    assert!(s64.replan_counts().unwrap().replans > 0);
}

#[test]
fn each_refusal_is_typed() {
    let img = image(&everything());
    let dec = |b: &[u8]| decode::<f32, 16, f32>(b, Layers::ALL).map(|_| ());
    assert_eq!(dec(&img), Ok(()));
    // Any flipped bit past the header is a CRC failure.
    for at in [12, 40, img.len() / 2, img.len() - 5, img.len() - 1] {
        let mut b = img.clone();
        b[at] ^= 0x10;
        assert_eq!(dec(&b), Err(ImageError::BadCrc), "byte {at}");
    }
    let mut b = img.clone();
    b[0] = b'X';
    assert_eq!(dec(&b), Err(ImageError::BadMagic));
    let mut b = img.clone();
    b[4..6].copy_from_slice(&(IMAGE_VERSION + 1).to_le_bytes());
    reseal(&mut b);
    assert_eq!(
        dec(&b),
        Err(ImageError::BadVersion {
            found: IMAGE_VERSION + 1
        })
    );
    assert_eq!(dec(&img[..img.len() - 1]), Err(ImageError::Size));
    assert_eq!(dec(&img[..10]), Err(ImageError::Size));
    // A build that does not fly a layer refuses the image naming it.
    let no_barrier = Layers {
        barrier: false,
        ..Layers::ALL
    };
    assert_eq!(
        decode::<f32, 16, f32>(&img, no_barrier).map(|_| ()),
        Err(ImageError::Unsupported(Layer::Barrier))
    );
    // A table larger than the build holds.
    assert_eq!(
        decode::<f32, 4, f32>(&img, Layers::ALL).map(|_| ()),
        Err(ImageError::TooManyNodes)
    );
    // A value the fixed point cannot hold (a period of 1e12 s).
    let mut c = everything();
    c.profile.guidance.period_s = 1e12;
    assert_eq!(
        decode::<Fixed, 16, f32>(&image(&c), Layers::ALL).map(|_| ()),
        Err(ImageError::Range)
    );
    // An enumeration out of range (the independent variable, byte 36), resealed.
    let mut b = img.clone();
    b[36] = 7;
    reseal(&mut b);
    assert_eq!(dec(&b), Err(ImageError::Malformed));
    // A layer mask that claims a layer the bytes do not hold.
    let mut b = image(&full().masked(Layers::PROFILE));
    b[6] |= 1 << 1;
    reseal(&mut b);
    assert_eq!(
        decode::<f32, 16, f32>(&b, Layers::ALL).map(|_| ()),
        Err(ImageError::Size)
    );
}

#[test]
fn chunks_reassemble_and_out_of_order_is_refused() {
    let img = image(&everything());
    let mut rx = ImageReceiver::<CAP>::new();
    let all: Vec<_> = chunks(&img).collect();
    assert_eq!(all.len(), img.len().div_ceil(CHUNK_BYTES));
    let mut got = None;
    for (i, n, d) in &all {
        if let Some(b) = rx.take(*i, *n, d).unwrap() {
            got = Some(b.to_vec());
        }
    }
    assert_eq!(got.as_deref(), Some(img.as_slice()));
    // Skipping a chunk: refused, and the next chunk 0 starts over.
    let mut rx = ImageReceiver::<CAP>::new();
    let (i0, n, d0) = all[0];
    assert_eq!(rx.take(i0, n, &d0), Ok(None));
    let (_, _, d2) = all[2];
    assert_eq!(rx.take(2, n, &d2), Err(ImageError::ChunkOrder));
    // An image longer than the receiver holds.
    let mut small = ImageReceiver::<{ CHUNK_BYTES }>::new();
    assert_eq!(small.take(0, n, &d0), Ok(None));
    let (_, _, d1) = all[1];
    assert_eq!(small.take(1, n, &d1), Err(ImageError::Size));
}
