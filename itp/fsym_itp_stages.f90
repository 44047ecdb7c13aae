!> The one place where a splitting table of the library (`scheme_t`: op codes and the
!> coefficient arrays c and u, see `fsym_scheme`) becomes a sequence of grid factors for the
!> imaginary-time Schroedinger equation d psi/d tau = (1/2 lap - V) psi = -(T + V) psi.
!>
!> **Derivation.** A table is a formal identity between exponentials of two operators A and B:
!> its stages multiply e^{c h A} (drift) and e^{c h (B + w h^2 [B,[A,B]])} (gradient kick with
!> w = u/c), and the product equals e^{h(A+B)} up to h^{p+1}. The classical kernel reads it
!> with the Lie operators A = {.,T}, B = {.,V} of T = p^2/2: e^{hB} is p <- p - h grad V, and
!> since {V,{T,V}} = -|grad V|^2, the gradient kick is the kick of the potential
!> c V - u h^2 |grad V|^2, i.e. p <- p + c h F + u h^3 grad|F|^2 with F = -grad V: the
!> convention of the tables (METHODS.md, "Conventions"). Imaginary time reads the same
!> identity with A = -T = lap/2, B = -V and h = tau; now [B,[A,B]] = -[V,[T,V]] = -|grad V|^2
!> (for T = -lap/2, [V,[T,V]] = |grad V|^2 exactly), so the stages become
!>
!> * drift (c)              psi <- F^-1 exp(-c tau |k|^2/2) F psi       (kinetic factor)
!> * kick (c)               psi <- exp(-c tau V) psi
!> * gradient kick (c, u)   psi <- exp(-tau (c V + u tau^2 |grad V|^2)) psi
!>
!> with the table's own c and u: the sign of the |grad V|^2 term is + here where the classical
!> potential has -, and no other factor enters. Running the stages in table order multiplies
!> the factors in the reverse order of the operator product; the reversed product approximates
!> e^{-tau H} to the same order, since reversal maps [B,[A,B]] to itself. A wrong sign of the
!> gradient term leaves a method of order 2 (the tests measure 4).
!>
!> **Forward only.** A drift with c < 0 is exp(+|c| tau |k|^2/2): backward diffusion, unbounded
!> in k (Sheng 1989, Suzuki 1991; Chin 2007, the paper's first argument for forward methods):
!> such a table is refused. Negative kick weights are bounded on a grid and allowed.
!>
!> **Extrapolated kicks (A')** replace the gradient term by a force at a shifted point,
!> F(q + s h^2 F). On the grid the analogue would be c V(x + (s/2) tau^2 grad V(x)), which
!> equals c V + u tau^2 |grad V|^2 + O(tau^4) (u = c s/2); it needs V off the grid points,
!> which an array V (or a Gross-Pitaevskii density) does not give, and it needs grad V, from
!> which |grad V|^2 is as cheap. So A' saves nothing here and is refused with a status
!> (use A: its gradient term costs no FFT for a fixed V).
!>
!> Two methods are not tables: `Strang` is the table V/2 T V/2 (built with
!> `fsym_scheme_custom`: one drift, two FFTs per step), and `CN` is the first-order split-step
!> Crank-Nicolson of the published Gross-Pitaevskii codes, psi <- C(tau) exp(-tau V) psi with
!> the Cayley factor C = (1 - tau |k|^2/4)/(1 + tau |k|^2/4) applied in Fourier space (spectral
!> in x, so that only its time discretisation differs from the others).
module fsym_itp_stages
    use fsym_kinds, only: wp
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_INCONSISTENT_SCHEME, &
                           FSYM_ERR_NO_MEMORY, fsym_report, fsym_pass
    use fsym_scheme, only: scheme_t, fsym_scheme_custom, OP_DRIFT, OP_KICK, OP_GRAD_KICK, &
                           OP_EXTRAP_KICK
    use fsym_paper_schemes, only: fsym_scheme_by_name
    implicit none
    private

    integer, parameter, public :: ITP_KINETIC = 1    !! exp(-c tau |k|^2/2) in Fourier space
    integer, parameter, public :: ITP_POTENTIAL = 2  !! exp(-tau (c V + u tau^2 |grad V|^2))
    integer, parameter, public :: ITP_CAYLEY = 3     !! (1 - tau|k|^2/4)/(1 + tau|k|^2/4)
    integer, parameter, public :: ITP_NAME_LEN = 24  !! length of a method name

    !> One grid stage: what it applies and with which weights.
    type, public :: fsym_itp_stage_t
        integer :: kind = 0           !! `ITP_KINETIC`, `ITP_POTENTIAL` or `ITP_CAYLEY`
        real(wp) :: c = 0.0_wp        !! weight of T (kinetic) or of V (potential)
        real(wp) :: u = 0.0_wp        !! weight of tau^2 |grad V|^2 (potential only)
    end type fsym_itp_stage_t

    public :: fsym_itp_stages_from_scheme, fsym_itp_method
    public :: fsym_itp_kinetic_exponent, fsym_itp_potential_exponent, fsym_itp_cayley

contains

    !> Grid stages of a library table (see the module text for the map); refused
    !> (`FSYM_ERR_INCONSISTENT_SCHEME`, `stages` untouched) for a negative drift weight or an
    !> extrapolated kick.
    subroutine fsym_itp_stages_from_scheme(scheme, stages, stat, errmsg)
        type(scheme_t), intent(in) :: scheme                        !! the table
        type(fsym_itp_stage_t), allocatable, intent(inout) :: stages(:)  !! its grid stages
        integer, intent(out), optional :: stat                      !! status code
        character(len=*), intent(inout), optional :: errmsg         !! message on error
        integer :: k
        character(len=16) :: buf
        do k = 1, scheme%nop
            write (buf, '(i0)') k
            if (scheme%op(k) == OP_DRIFT .and. scheme%c(k) < 0.0_wp) then
                call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'imaginary time: '// &
                                 scheme%name//' has a negative drift weight at stage '// &
                                 trim(buf)//' (backward diffusion, unbounded; only forward '// &
                                 'methods apply)', stat, errmsg)
                return
            end if
            if (scheme%op(k) == OP_EXTRAP_KICK) then
                call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'imaginary time: '// &
                                 scheme%name//' extrapolates its kick (stage '//trim(buf)// &
                                 '): V off the grid is not available, use the gradient form', &
                                 stat, errmsg)
                return
            end if
        end do
        if (allocated(stages)) deallocate (stages)
        allocate (stages(scheme%nop), stat=k)
        if (k /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'imaginary time: stage table', stat, errmsg)
            return
        end if
        do k = 1, scheme%nop
            select case (scheme%op(k))
            case (OP_DRIFT)
                stages(k) = fsym_itp_stage_t(ITP_KINETIC, scheme%c(k), 0.0_wp)
            case (OP_KICK)
                stages(k) = fsym_itp_stage_t(ITP_POTENTIAL, scheme%c(k), 0.0_wp)
            case (OP_GRAD_KICK)
                stages(k) = fsym_itp_stage_t(ITP_POTENTIAL, scheme%c(k), scheme%u(k))
            case default
                ! op codes are validated when a scheme is built
            end select
        end do
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_itp_stages_from_scheme

    !> Grid stages of a method label: `CN` (split-step Crank-Nicolson, order 1), `Strang`
    !> (V/2 T V/2, order 2), or any label of `fsym_scheme_by_name` (A, C, A4, A5, ...).
    subroutine fsym_itp_method(label, stages, order, name, stat, errmsg)
        character(len=*), intent(in) :: label                       !! method label
        type(fsym_itp_stage_t), allocatable, intent(inout) :: stages(:)  !! its grid stages
        integer, intent(out) :: order                               !! its order in tau
        character(len=ITP_NAME_LEN), intent(out) :: name            !! its name
        integer, intent(out), optional :: stat                      !! status code
        character(len=*), intent(inout), optional :: errmsg         !! message on error
        type(scheme_t) :: s
        integer :: st
        character(len=256) :: msg
        name = adjustl(label)
        if (lower(trim(adjustl(label))) == 'cn') then
            if (allocated(stages)) deallocate (stages)
            stages = [fsym_itp_stage_t(ITP_POTENTIAL, 1.0_wp, 0.0_wp), &
                      fsym_itp_stage_t(ITP_CAYLEY, 1.0_wp, 0.0_wp)]
            order = 1
            name = 'CN'
            if (present(stat)) stat = FSYM_SUCCESS
            return
        end if
        msg = ''
        if (lower(trim(adjustl(label))) == 'strang') then
            call fsym_scheme_custom('Strang', [OP_KICK, OP_DRIFT, OP_KICK], &
                                    [0.5_wp, 1.0_wp, 0.5_wp], [0.0_wp, 0.0_wp, 0.0_wp], 2, &
                                    s, st, msg)
        else
            call fsym_scheme_by_name(label, s, st, msg)
        end if
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg)
            return
        end if
        call fsym_itp_stages_from_scheme(s, stages, st, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg)
            return
        end if
        order = s%order
        name = s%name
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_itp_method

    !> Exponent of the kinetic factor of a drift of weight c: -c tau |k|^2/2.
    pure elemental real(wp) function fsym_itp_kinetic_exponent(c, tau, k2) result(e)
        real(wp), intent(in) :: c      !! drift weight
        real(wp), intent(in) :: tau    !! imaginary-time step
        real(wp), intent(in) :: k2     !! |k|^2
        e = -c * tau * 0.5_wp * k2
    end function fsym_itp_kinetic_exponent

    !> Exponent of the potential factor of a (gradient) kick: -tau (c V + u tau^2 |grad V|^2).
    pure elemental real(wp) function fsym_itp_potential_exponent(c, u, tau, v, gsq) result(e)
        real(wp), intent(in) :: c      !! kick weight
        real(wp), intent(in) :: u      !! gradient weight (0 for a plain kick)
        real(wp), intent(in) :: tau    !! imaginary-time step
        real(wp), intent(in) :: v      !! potential
        real(wp), intent(in) :: gsq    !! |grad V|^2
        e = -tau * (c * v + u * tau * tau * gsq)
    end function fsym_itp_potential_exponent

    !> The Crank-Nicolson (Cayley) kinetic factor (1 - tau |k|^2/4)/(1 + tau |k|^2/4).
    pure elemental real(wp) function fsym_itp_cayley(tau, k2) result(f)
        real(wp), intent(in) :: tau    !! imaginary-time step
        real(wp), intent(in) :: k2     !! |k|^2
        f = (1.0_wp - 0.25_wp * tau * k2) / (1.0_wp + 0.25_wp * tau * k2)
    end function fsym_itp_cayley

    pure function lower(s) result(t)
        character(len=*), intent(in) :: s
        character(len=len(s)) :: t
        integer :: i
        t = s
        do i = 1, len(s)
            if (s(i:i) >= 'A' .and. s(i:i) <= 'Z') t(i:i) = achar(iachar(s(i:i)) + 32)
        end do
    end function lower

end module fsym_itp_stages
