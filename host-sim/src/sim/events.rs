//! The events located inside integration steps: atmosphere exit and re-entry at the
//! interface altitude, and the terminations (altitude, Mach number, normalised energy,
//! ground). Each event is a zero crossing of [`Event::value`] in its [`Event::direction`].

use super::{Termination, TerminationReason};
use crate::integrate::Direction;

/// An event of the closed loop. The order of [`Event::ALL`] is the integrator's event index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event {
    /// Rising through the interface altitude (atmosphere exit).
    Exit,
    /// Falling through the interface altitude (re-entry).
    Entry,
    /// Falling through the termination altitude.
    Altitude,
    /// Falling through the termination Mach number.
    Mach,
    /// Falling through the termination normalised energy.
    NormalizedEnergy,
    /// Reaching the surface.
    Ground,
}

/// What the event functions need at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventState {
    /// Altitude above the sphere \[m\].
    pub altitude_m: f64,
    /// Mach number \[-\] (0 where not evaluated or undefined).
    pub mach: f64,
    /// Normalised energy \[-\], if evaluated and defined.
    pub normalized_energy: Option<f64>,
}

impl Event {
    /// Every event, in integrator index order.
    pub const ALL: [Event; 6] = [
        Event::Exit,
        Event::Entry,
        Event::Altitude,
        Event::Mach,
        Event::NormalizedEnergy,
        Event::Ground,
    ];

    /// The event of integrator index `i`.
    #[must_use]
    pub fn from_index(i: usize) -> Option<Self> {
        Self::ALL.get(i).copied()
    }

    /// The crossing direction that triggers the event.
    #[must_use]
    pub fn direction(self) -> Direction {
        match self {
            Event::Exit => Direction::Rising,
            _ => Direction::Falling,
        }
    }

    /// The termination this event causes, if any (exit and re-entry do not stop the run).
    #[must_use]
    pub fn termination(self) -> Option<TerminationReason> {
        match self {
            Event::Exit | Event::Entry => None,
            Event::Altitude => Some(TerminationReason::Altitude),
            Event::Mach => Some(TerminationReason::Mach),
            Event::NormalizedEnergy => Some(TerminationReason::NormalizedEnergy),
            Event::Ground => Some(TerminationReason::Ground),
        }
    }

    /// Whether the event needs the flight conditions (Mach, energy) under `term`.
    #[must_use]
    pub fn needs_conditions(term: &Termination) -> bool {
        term.mach.is_some() || term.normalized_energy.is_some()
    }

    /// The event function at state `s` (interface altitude `interface_m` \[m\]); a disabled
    /// termination is the constant 1 (never crosses).
    #[must_use]
    pub fn value(self, s: &EventState, interface_m: f64, term: &Termination) -> f64 {
        match self {
            Event::Exit | Event::Entry => s.altitude_m - interface_m,
            Event::Altitude => term.altitude_m.map_or(1.0, |ht| s.altitude_m - ht),
            Event::Mach => match term.mach {
                Some(m) if s.mach > 0.0 => s.mach - m,
                _ => 1.0,
            },
            Event::NormalizedEnergy => match (term.normalized_energy, s.normalized_energy) {
                (Some(e), Some(v)) => v - e,
                _ => 1.0,
            },
            Event::Ground => s.altitude_m,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_round_trip_and_only_exit_rises() {
        for (i, e) in Event::ALL.iter().enumerate() {
            assert_eq!(Event::from_index(i), Some(*e));
            assert_eq!(e.direction() == Direction::Rising, *e == Event::Exit);
        }
        assert_eq!(Event::from_index(Event::ALL.len()), None);
    }

    #[test]
    fn disabled_terminations_never_cross() {
        let term = Termination {
            altitude_m: None,
            mach: None,
            normalized_energy: None,
            max_time_s: 10.0,
        };
        let s = EventState {
            altitude_m: 5.0,
            mach: 3.0,
            normalized_energy: Some(0.1),
        };
        for e in [Event::Altitude, Event::Mach, Event::NormalizedEnergy] {
            assert_eq!(e.value(&s, 100.0, &term), 1.0);
        }
        assert_eq!(Event::Ground.value(&s, 100.0, &term), 5.0);
        assert_eq!(Event::Exit.value(&s, 100.0, &term), -95.0);
    }
}
