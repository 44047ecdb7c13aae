!> The umbrella module of forward-symplectic, fourth-order forward and non-forward symplectic
!> integrators for classical dynamics (S. A. Chin): `use fsym` gives the public API.
module fsym
    use fsym_kinds, only: wp, ik
    use fsym_status
    use fsym_scheme
    use fsym_paper_schemes
    use fsym_force
    use fsym_stepper
    use fsym_integrator
    use fsym_rkn
    use fsym_methods
    use fsym_kepler
    use fsym_models
    use fsym_nbody
    use fsym_kepler_universal
    use fsym_planets
    use fsym_processed
    use fsym_trace
    use fsym_analysis
    use fsym_checks
    use fsym_nbody_frequency
    ! The studies (linear stability through LAPACK, FPU chains, stability runs, the paper's
    ! diagnostics) are not part of the library: they live beside the programs in app/.
    implicit none
    public

    character(len=*), parameter :: FSYM_VERSION = '0.1.0'  !! library version
end module fsym
