//! The `speeds` statement: speeds of the user's choice in place of the
//! rates of some coordinates, with each rate given linear in them.

use super::Resolver;
use super::evaluate::KINEMATICS;
use super::list;
use super::scope::Binding;
use crate::expr::{ExprId, Sym, SymKinds};
use crate::language::ast::Field;
use crate::model::Speed;
use proc_macro2::Ident;

impl Resolver {
    /// `speeds w1, w2 { q1: rate1, q2: rate2 };`: the speeds `w` replace
    /// those of the coordinates named (`dt(q)`), taking their places in `v`
    /// in order, and `dt(qᵢ) = rateᵢ`, linear in the new speeds.
    pub(super) fn speeds_statement(&mut self, keyword: &Ident, names: &[Ident], rates: &[Field]) {
        if self.used_dt {
            self.errors.push(
                keyword.span(),
                "a `speeds` statement must come before every `dt(..)`: it changes what \
                 the speeds of its coordinates are",
            );
        }
        let replaced = self.replaced_speeds(rates);
        if names.len() != rates.len() {
            self.errors.push(
                keyword.span(),
                format!(
                    "{} new speed(s) for the rates of {} coordinate(s): a `speeds` \
                     statement replaces as many speeds as it names",
                    names.len(),
                    rates.len()
                ),
            );
        }
        if names.len() != replaced.len() {
            names.iter().for_each(|name| {
                self.define(name, Binding::Invalid);
            });
            return;
        }
        let mut slots: Vec<usize> = replaced.iter().map(|&(_, k)| k).collect();
        slots.sort_unstable();
        for (name, &k) in names.iter().zip(&slots) {
            self.model.speeds[k] = Speed {
                name: name.clone(),
                rate_of_coordinate: false,
            };
            self.define(name, Binding::Scalar(Sym::Speed(k as u32)));
        }
        for (field, &(i, _)) in rates.iter().zip(&replaced) {
            if let Some(rate) = self.rate_in_new_speeds(field, names, &slots) {
                self.set_rate(i, rate);
            }
        }
    }

    /// The coordinates whose rates a `speeds` statement gives, with their
    /// speeds' places: each a coordinate whose speed is still its rate,
    /// once.
    fn replaced_speeds(&mut self, rates: &[Field]) -> Vec<(u32, usize)> {
        let mut replaced: Vec<(u32, usize)> = Vec::new();
        for field in rates {
            match self.replaceable_speed(&field.name) {
                Some(pair) if replaced.iter().all(|&(i, _)| i != pair.0) => replaced.push(pair),
                Some(_) => self.errors.push(
                    field.name.span(),
                    format!("the rate of `{}` is given twice", field.name),
                ),
                None => self.errors.push(
                    field.name.span(),
                    format!(
                        "`{}` is not a coordinate whose speed is still `dt({})`: a `speeds` \
                         statement gives the rates of coordinates of `coordinates` \
                         statements, once",
                        field.name, field.name
                    ),
                ),
            }
        }
        replaced
    }

    /// The rate of `field`, checked: written without `dt(..)`, linear in
    /// the new speeds `names` (at `slots` of `v`) and in no other.
    fn rate_in_new_speeds(
        &mut self,
        field: &Field,
        names: &[Ident],
        slots: &[usize],
    ) -> Option<ExprId> {
        let read_dt = std::mem::replace(&mut self.used_dt, false);
        let rate = self.scalar(&field.value, KINEMATICS);
        if std::mem::replace(&mut self.used_dt, read_dt) {
            self.errors.push(
                field.value.range(),
                "a rate is written in the new speeds, without `dt(..)`",
            );
            return None;
        }
        let rate = rate?;
        let foreign = self
            .pool
            .free_symbols(rate)
            .into_iter()
            .any(|sym| matches!(sym, Sym::Speed(k) if !slots.contains(&(k as usize))));
        let linear = slots.iter().all(|&k| {
            let d = self.pool.diff(rate, Sym::Speed(k as u32));
            !self.pool.kinds(d).intersects(SymKinds::SPEED)
        });
        if foreign || !linear {
            let written: Vec<String> = names.iter().map(ToString::to_string).collect();
            let written: Vec<&str> = written.iter().map(String::as_str).collect();
            self.errors.push(
                field.value.range(),
                format!(
                    "the rate of `{}` must be linear in the speeds of this statement ({}), \
                     with coefficients of coordinates and parameters",
                    field.name,
                    list(&written)
                ),
            );
            return None;
        }
        Some(rate)
    }

    /// `dt(qᵢ) = rate`, with the divisors where it is undefined.
    fn set_rate(&mut self, i: u32, rate: ExprId) {
        self.pool.set_rate(i, rate);
        // Angular velocities computed before read the old rate.
        self.kinematics = None;
        let divisors = &mut self.model.rate_divisors;
        crate::model::singular::collect_rate_divisors(&mut self.pool, i as usize, rate, divisors);
    }

    /// The coordinate `name` and its speed, if the speed is still its rate
    /// `dt(name)`.
    pub(super) fn replaceable_speed(&self, name: &Ident) -> Option<(u32, usize)> {
        let Some((Binding::Scalar(Sym::Coord(i)), _)) = self.bindings.get(&name.to_string()) else {
            return None;
        };
        let k = self
            .model
            .speeds
            .iter()
            .position(|s| s.rate_of_coordinate && s.name == *name)?;
        Some((*i, k))
    }
}
