!> The state of the one splitting kernel (`fsym_kernel`): where each array lives in the
!> caller's work array, what the force cache holds, the step in progress and the counters.
!> Apart from the kernel so that a force model's own fused stepper (`force_model_t%advance`)
!> can advance it as the kernel would.
module fsym_kernel_state
    use fsym_kinds, only: wp, ik
    implicit none
    private

    integer, parameter, public :: KERNEL_SUSPEND = -1  !! model stat / kernel stat: suspended
    integer, parameter, public :: REQ_NONE = 0           !! no force outstanding
    integer, parameter, public :: REQ_FORCE = 1          !! a(q) into slot `ia`
    integer, parameter, public :: REQ_GRADIENT = 2       !! g(q) into slot `ig` (a(q) in `ia`)
    integer, parameter, public :: REQ_FORCE_SHIFTED = 3  !! a(x) into `iae`, x in slot `iqe`

    !> The kernel's state: where each array lives in the work array, what the cache holds,
    !> the step in progress and the counters.
    type, public :: kernel_state_t
        integer :: d = 0, n = 0             !! dimensions, particles
        integer :: nslot = 0                !! slots of d*n reals in the work array
        integer :: ia = 1, ig = 1           !! slots: acceleration, gradient term at q
        integer :: iqe = 1, iae = 1         !! slots: shifted point, acceleration there
        integer :: iq0 = 1, iv0 = 1         !! slots: q, v on entry to the step
        integer :: iqlast = 1               !! slot: q the cached force belongs to
        integer :: iqc = 1, ivc = 1         !! slots: compensation terms of q, v
        integer :: iqc0 = 1, ivc0 = 1       !! slots: compensation terms on entry
        logical :: comp = .false.           !! Kahan-compensated updates
        logical :: have_a = .false., have_g = .false., have_x = .false.
            !! slots ia, ig, iae hold valid forces
        logical :: active = .false.         !! a suspended step is in progress
        integer :: pc = 0                   !! stage in progress, or that failed (0: on entry)
        integer :: req = REQ_NONE           !! force outstanding while suspended
        real(wp) :: h = 0.0_wp              !! step of the step in progress
        real(wp) :: xshift = 0.0_wp         !! u h^2 of the cached extrapolated force
        integer(ik) :: nf = 0, ng = 0       !! force and gradient evaluations accepted
    end type kernel_state_t

end module fsym_kernel_state
