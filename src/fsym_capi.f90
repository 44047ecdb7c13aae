!> C face of forward-symplectic (`include/fsym.h`): an opaque handle to an allocated
!> `integrator_t`, an acceleration callback (and optionally a gradient-term callback) that
!> receive the caller's `void *user`, and an integer status from every call. It drives the
!> same kernel as the modern API through `integrator_t`, so it gives the same numbers bit for
!> bit. Nothing here stops: every error is a returned status.
!>
!> Arrays are C arrays `double q[n][d]`, i.e. Fortran `q(d, n)`.
module fsym_capi
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_ptr, c_funptr, &
                                           c_long_long, c_null_ptr, c_null_funptr, c_null_char, &
                                           c_associated, c_f_pointer, c_f_procpointer, c_loc
    use fsym_kinds, only: wp, ik
    use fsym_status, only: fsym_status_message, FSYM_SUCCESS, FSYM_ERR_BAD_PARAMETER, &
                           FSYM_ERR_NO_GRADIENT, FSYM_ERR_NOT_INITIALIZED, FSYM_ERR_CAPACITY
    use fsym_force, only: force_model_t
    use fsym_integrator, only: integrator_t
    implicit none
    private

    public :: fsym_c_create, fsym_c_step, fsym_c_counts, fsym_c_destroy, fsym_c_message

    abstract interface
        !> C acceleration callback: `int accel(int d, int n, const double *q, double *a,
        !> void *user)`; non-zero return = failure.
        integer(c_int) function c_accel_iface(d, n, q, a, user) bind(C)
            import :: c_int, c_double, c_ptr
            implicit none
            integer(c_int), value :: d, n
            real(c_double), intent(in) :: q(*)
            real(c_double), intent(out) :: a(*)
            type(c_ptr), value :: user
        end function c_accel_iface
        !> C gradient-term callback: `int grad(int d, int n, const double *q,
        !> const double *a, double *g, void *user)`; non-zero return = failure.
        integer(c_int) function c_grad_iface(d, n, q, a, g, user) bind(C)
            import :: c_int, c_double, c_ptr
            implicit none
            integer(c_int), value :: d, n
            real(c_double), intent(in) :: q(*), a(*)
            real(c_double), intent(out) :: g(*)
            type(c_ptr), value :: user
        end function c_grad_iface
    end interface

    !> A force model calling C function pointers with the caller's user data.
    type, extends(force_model_t) :: c_model_t
        type(c_funptr) :: accel = c_null_funptr   ! C function pointers, converted at the call
        type(c_funptr) :: grad = c_null_funptr
        type(c_ptr) :: user = c_null_ptr
    contains
        procedure :: acceleration => c_model_acceleration
        procedure :: gradient => c_model_gradient
        procedure :: has_gradient => c_model_has_gradient
    end type c_model_t

    !> What a C handle points to.
    type :: c_handle_t
        type(integrator_t) :: it
        type(c_model_t) :: model
        integer :: d = 0, n = 0
    end type c_handle_t

contains

    subroutine c_model_acceleration(self, q, a, stat)
        class(c_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(out), contiguous :: a(:, :)
        integer, intent(inout) :: stat
        procedure(c_accel_iface), pointer :: f
        call c_f_procpointer(self%accel, f)
        stat = int(f(int(size(q, 1), c_int), int(size(q, 2), c_int), q, a, self%user))
    end subroutine c_model_acceleration

    subroutine c_model_gradient(self, q, a, g, stat)
        class(c_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(in), contiguous :: a(:, :)
        real(wp), intent(out), contiguous :: g(:, :)
        integer, intent(inout) :: stat
        procedure(c_grad_iface), pointer :: f
        if (.not. c_associated(self%grad)) then
            g = 0.0_wp; stat = FSYM_ERR_NO_GRADIENT; return
        end if
        call c_f_procpointer(self%grad, f)
        stat = int(f(int(size(q, 1), c_int), int(size(q, 2), c_int), q, a, g, self%user))
    end subroutine c_model_gradient

    logical function c_model_has_gradient(self)
        class(c_model_t), intent(in) :: self
        c_model_has_gradient = c_associated(self%grad)
    end function c_model_has_gradient

    !> `int fsym_create(const char *method, int d, int n, fsym_accel_fn accel,
    !> fsym_grad_fn grad, void *user, fsym_integrator **handle)`: a new integrator for the
    !> method label on arrays (d, n). `grad` may be NULL (then methods with a gradient kick
    !> are refused; use their primed form). `*handle` is NULL on failure.
    integer(c_int) function fsym_c_create(method, d, n, accel, grad, user, handle) &
        bind(C, name='fsym_create') result(stat)
        character(kind=c_char), intent(in) :: method(*)   !! NUL-terminated method label
        integer(c_int), value :: d, n                     !! dimensions, bodies
        type(c_funptr), value :: accel                    !! acceleration callback
        type(c_funptr), value :: grad                     !! gradient callback or NULL
        type(c_ptr), value :: user                        !! passed to the callbacks
        type(c_ptr), intent(out) :: handle                !! the new integrator
        type(c_handle_t), pointer :: p
        character(len=:), allocatable :: name
        character(len=256) :: msg
        integer :: k, st
        handle = c_null_ptr
        if (.not. c_associated(accel)) then
            stat = FSYM_ERR_BAD_PARAMETER; return
        end if
        name = ''
        do k = 1, 64
            if (method(k) == c_null_char) exit
            name = name//method(k)
        end do
        allocate (p, stat=st)
        if (st /= 0) then
            stat = FSYM_ERR_CAPACITY; return
        end if
        p%model%accel = accel
        p%model%grad = grad
        p%model%user = user
        call p%it%init_by_name(name, p%model, int(d), int(n), st, msg)
        if (st /= FSYM_SUCCESS) then
            deallocate (p)
            stat = int(st, c_int); return
        end if
        p%d = d; p%n = n
        handle = c_loc(p)
        stat = FSYM_SUCCESS
    end function fsym_c_create

    !> `int fsym_step(fsym_integrator *handle, double *q, double *v, double h, int nstep)`:
    !> nstep steps of size h. On failure q and v hold the state after the last completed step.
    integer(c_int) function fsym_c_step(handle, q, v, h, nstep) bind(C, name='fsym_step') &
        result(stat)
        type(c_ptr), value :: handle       !! integrator
        type(c_ptr), value :: q, v         !! positions, velocities: double[n][d]
        real(c_double), value :: h         !! step
        integer(c_int), value :: nstep     !! number of steps
        type(c_handle_t), pointer :: p
        real(wp), pointer, contiguous :: qf(:, :), vf(:, :)
        character(len=256) :: msg
        integer :: st
        if (.not. (c_associated(handle) .and. c_associated(q) .and. c_associated(v))) then
            stat = FSYM_ERR_NOT_INITIALIZED; return
        end if
        call c_f_pointer(handle, p)
        call c_f_pointer(q, qf, [p%d, p%n])
        call c_f_pointer(v, vf, [p%d, p%n])
        st = FSYM_SUCCESS
        if (nstep > 0) call p%it%run(p%model, qf, vf, real(h, wp), int(nstep), st, msg)
        stat = int(st, c_int)
    end function fsym_c_step

    !> `int fsym_counts(const fsym_integrator *handle, long long *nforce, long long *ngrad)`:
    !> force and gradient evaluations so far.
    integer(c_int) function fsym_c_counts(handle, nforce, ngrad) bind(C, name='fsym_counts') &
        result(stat)
        type(c_ptr), value :: handle                  !! integrator
        integer(c_long_long), intent(out) :: nforce   !! force evaluations
        integer(c_long_long), intent(out) :: ngrad    !! gradient evaluations
        type(c_handle_t), pointer :: p
        integer(ik) :: nf, ng
        nforce = 0; ngrad = 0
        if (.not. c_associated(handle)) then
            stat = FSYM_ERR_NOT_INITIALIZED; return
        end if
        call c_f_pointer(handle, p)
        nf = p%it%force_evaluations(); ng = p%it%gradient_evaluations()
        nforce = int(nf, c_long_long); ngrad = int(ng, c_long_long)
        stat = FSYM_SUCCESS
    end function fsym_c_counts

    !> `void fsym_destroy(fsym_integrator *handle)`: free the integrator (NULL is ignored).
    subroutine fsym_c_destroy(handle) bind(C, name='fsym_destroy')
        type(c_ptr), value :: handle   !! integrator
        type(c_handle_t), pointer :: p
        if (.not. c_associated(handle)) return
        call c_f_pointer(handle, p)
        call p%it%destroy()
        deallocate (p)
    end subroutine fsym_c_destroy

    !> `void fsym_status_message(int code, char *buf, int len)`: NUL-terminated text of a
    !> status code, cut to fit `len` bytes.
    subroutine fsym_c_message(code, buf, buflen) bind(C, name='fsym_status_message')
        integer(c_int), value :: code              !! status code
        character(kind=c_char), intent(out) :: buf(*)  !! receives the text
        integer(c_int), value :: buflen            !! size of buf in bytes
        character(len=:), allocatable :: text
        integer :: k, m
        if (buflen < 1) return
        text = fsym_status_message(int(code))
        m = min(len(text), int(buflen) - 1)
        do k = 1, m
            buf(k) = text(k:k)
        end do
        buf(m + 1) = c_null_char
    end subroutine fsym_c_message

end module fsym_capi
