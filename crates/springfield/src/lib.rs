//! The Spring-Field: spring models between mesh nodes and the damped explicit pseudo-time solver that balances them, shared by the 2D and 3D advancing-front meshers.
