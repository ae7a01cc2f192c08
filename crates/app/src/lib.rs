//! atmos
