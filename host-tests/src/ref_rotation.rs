//! Reserved for the reference of its issue; see the crate docs.
