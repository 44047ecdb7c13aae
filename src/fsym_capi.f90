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
    use fsym_status, only: fsym_status_message, FSYM_SUCCESS, FSYM_ERR_BAD_ARGUMENT, &
                           FSYM_ERR_NO_GRADIENT, FSYM_ERR_NOT_INITIALIZED, FSYM_ERR_CAPACITY, &
                           FSYM_ERR_BUSY
    use fsym_force, only: force_model_t
    use fsym_integrator, only: integrator_t
    use fsym_stepper, only: observer_t
    implicit none
    private

    public :: fsym_c_create, fsym_c_step, fsym_c_counts, fsym_c_destroy, fsym_c_message
    public :: fsym_c_steps_done, fsym_c_last_message, fsym_c_reset_cache
    public :: fsym_c_checkpoint_length, fsym_c_checkpoint_save, fsym_c_checkpoint_load
    public :: fsym_c_time, fsym_c_run_to, fsym_c_set_observer
    public :: fsym_c_set_guard

    !> Longest method label read from C (longer ones are refused, never cut).
    integer, parameter, public :: FSYM_C_NAME_MAX = 256

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
        !> C observer callback: `int observe(int d, int n, const double *q, const double *v,
        !> double t, long long step, void *user)`; non-zero return = stop the run there.
        integer(c_int) function c_observe_iface(d, n, q, v, t, step, user) bind(C)
            import :: c_int, c_double, c_ptr, c_long_long
            implicit none
            integer(c_int), value :: d, n
            real(c_double), intent(in) :: q(*), v(*)
            real(c_double), value :: t
            integer(c_long_long), value :: step
            type(c_ptr), value :: user
        end function c_observe_iface
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
        !> C local-frequency callback: `int freq(int d, int n, const double *q,
        !> double *omega2, double *r, void *user)`; non-zero return = failure.
        integer(c_int) function c_freq_iface(d, n, q, omega2, r, user) bind(C)
            import :: c_int, c_double, c_ptr
            implicit none
            integer(c_int), value :: d, n
            real(c_double), intent(in) :: q(*)
            real(c_double), intent(out) :: omega2, r
            type(c_ptr), value :: user
        end function c_freq_iface
    end interface

    !> A force model calling C function pointers with the caller's user data.
    type, extends(force_model_t) :: c_model_t
        type(c_funptr) :: accel = c_null_funptr   ! C function pointers, converted at the call
        type(c_funptr) :: grad = c_null_funptr
        type(c_funptr) :: freq = c_null_funptr    ! local frequency (the guard), or NULL
        type(c_ptr) :: user = c_null_ptr
    contains
        procedure :: acceleration => c_model_acceleration
        procedure :: gradient => c_model_gradient
        procedure :: has_gradient => c_model_has_gradient
        procedure :: local_frequency => c_model_frequency
        procedure :: has_frequency => c_model_has_frequency
    end type c_model_t

    !> An observer calling a C function pointer with the caller's user data.
    type, extends(observer_t) :: c_observer_t
        type(c_funptr) :: f = c_null_funptr
        type(c_ptr) :: user = c_null_ptr
        integer :: every = 1
    contains
        procedure :: observe => c_observer_observe
    end type c_observer_t

    !> The first component of a live handle; `fsym_destroy` overwrites it.
    integer(c_int), parameter :: LIVE = 1718837608, DEAD = 1684366433

    !> What a C handle points to.
    type :: c_handle_t
        integer(c_int) :: magic = LIVE        ! LIVE until destroyed
        type(integrator_t) :: it
        type(c_model_t) :: model
        type(c_observer_t) :: obs
        integer :: d = 0, n = 0
        integer(ik) :: last_done = 0          ! steps completed by the last fsym_step
        character(len=512) :: msg = ''        ! message of the last failing call
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

    subroutine c_model_frequency(self, q, omega2, r, stat)
        class(c_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(out) :: omega2, r
        integer, intent(inout) :: stat
        procedure(c_freq_iface), pointer :: f
        omega2 = 0.0_wp; r = 0.0_wp
        if (.not. c_associated(self%freq)) then
            stat = 1; return
        end if
        call c_f_procpointer(self%freq, f)
        stat = int(f(int(size(q, 1), c_int), int(size(q, 2), c_int), q, omega2, r, self%user))
    end subroutine c_model_frequency

    logical function c_model_has_frequency(self)
        class(c_model_t), intent(in) :: self
        c_model_has_frequency = c_associated(self%freq)
    end function c_model_has_frequency

    !> `int fsym_set_guard(fsym_integrator *handle, fsym_freq_fn freq, double fraction)`:
    !> the step-size guard (as `integrator_t%set_guard`) with the caller's local frequency
    !> `freq` (largest omega^2 at q and the distance where it occurs); `fraction` of x*
    !> (<= 0: 1). A NULL `freq` turns the guard off. Refused steps: FSYM_ERR_STEP_TOO_LARGE.
    integer(c_int) function fsym_c_set_guard(handle, freq, fraction) &
        bind(C, name='fsym_set_guard') result(stat)
        type(c_ptr), value :: handle          !! integrator
        type(c_funptr), value :: freq         !! local-frequency callback, or NULL
        real(c_double), value :: fraction     !! of x* (<= 0: 1)
        type(c_handle_t), pointer :: p
        integer :: st
        stat = FSYM_ERR_NOT_INITIALIZED
        if (.not. live_handle(handle, p)) return
        p%msg = ''
        if (.not. c_associated(freq)) then
            call p%it%set_guard(p%model, .false., st, p%msg)
        else
            p%model%freq = freq
            if (fraction > 0.0_wp) then
                call p%it%set_guard(p%model, .true., st, p%msg, real(fraction, wp))
            else
                call p%it%set_guard(p%model, .true., st, p%msg)
            end if
        end if
        stat = int(st, c_int)
    end function fsym_c_set_guard

    !> The handle behind a C pointer when it is a live one (not NULL, not destroyed).
    logical function live_handle(handle, p)
        type(c_ptr), intent(in) :: handle
        type(c_handle_t), pointer, intent(out) :: p
        live_handle = .false.; p => null()
        if (.not. c_associated(handle)) return
        call c_f_pointer(handle, p)
        live_handle = p%magic == LIVE
    end function live_handle

    logical function c_model_has_gradient(self)
        class(c_model_t), intent(in) :: self
        c_model_has_gradient = c_associated(self%grad)
    end function c_model_has_gradient

    !> `int fsym_create(const char *method, int d, int n, fsym_accel_fn accel,
    !> fsym_grad_fn grad, void *user, fsym_integrator **handle)`: a new integrator for the
    !> method label on arrays (d, n). `grad` may be NULL (then methods with a gradient kick
    !> are refused; use their primed form). `*handle` is NULL on failure. NULL `method`,
    !> `accel` or `handle`, and a label longer than FSYM_C_NAME_MAX characters, give
    !> FSYM_ERR_BAD_ARGUMENT.
    integer(c_int) function fsym_c_create(method, d, n, accel, grad, user, handle) &
        bind(C, name='fsym_create') result(stat)
        type(c_ptr), value :: method                      !! NUL-terminated method label
        integer(c_int), value :: d, n                     !! dimensions, bodies
        type(c_funptr), value :: accel                    !! acceleration callback
        type(c_funptr), value :: grad                     !! gradient callback or NULL
        type(c_ptr), value :: user                        !! passed to the callbacks
        type(c_ptr), value :: handle                      !! where the new integrator goes
        type(c_handle_t), pointer :: p
        type(c_ptr), pointer :: out
        character(kind=c_char), pointer :: chars(:)
        character(len=FSYM_C_NAME_MAX) :: name
        character(len=256) :: msg
        integer :: k, st, nlen
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. c_associated(handle)) return
        call c_f_pointer(handle, out)
        out = c_null_ptr
        if (.not. (c_associated(accel) .and. c_associated(method))) return
        call c_f_pointer(method, chars, [FSYM_C_NAME_MAX + 1])
        nlen = -1
        do k = 1, FSYM_C_NAME_MAX + 1
            if (chars(k) == c_null_char) then
                nlen = k - 1; exit
            end if
        end do
        if (nlen < 0) return
        name = ''
        do k = 1, nlen
            name(k:k) = chars(k)
        end do
        allocate (p, stat=st)
        if (st /= 0) then
            stat = FSYM_ERR_CAPACITY; return
        end if
        p%model%accel = accel
        p%model%grad = grad
        p%model%user = user
        call p%it%init_by_name(name(1:nlen), p%model, int(d), int(n), st, msg)
        if (st /= FSYM_SUCCESS) then
            deallocate (p)
            stat = int(st, c_int); return
        end if
        p%d = d; p%n = n
        p%magic = LIVE
        out = c_loc(p)
        stat = FSYM_SUCCESS
    end function fsym_c_create

    !> `int fsym_step(fsym_integrator *handle, double *q, double *v, double h, int nstep)`:
    !> nstep steps of size h. On failure q and v hold the state after the last completed step
    !> (`fsym_steps_done` tells how many, `fsym_last_message` what went wrong). nstep <= 0
    !> and NULL q or v give FSYM_ERR_BAD_ARGUMENT; a NULL handle FSYM_ERR_NOT_INITIALIZED.
    integer(c_int) function fsym_c_step(handle, q, v, h, nstep) bind(C, name='fsym_step') &
        result(stat)
        type(c_ptr), value :: handle       !! integrator
        type(c_ptr), value :: q, v         !! positions, velocities: double[n][d]
        real(c_double), value :: h         !! step
        integer(c_int), value :: nstep     !! number of steps
        stat = c_run(handle, q, v, h, int(nstep), 0.0_wp, .false.)
    end function fsym_c_step

    !> `fsym_step` (`to` false: `nstep` steps) and `fsym_run_to` (`to`: up to `t_end`).
    integer(c_int) function c_run(handle, q, v, h, nstep, t_end, to) result(stat)
        type(c_ptr), intent(in) :: handle, q, v
        real(c_double), intent(in) :: h
        integer, intent(in) :: nstep
        real(wp), intent(in) :: t_end
        logical, intent(in) :: to
        type(c_handle_t), pointer :: p
        real(wp), pointer, contiguous :: qf(:, :), vf(:, :)
        integer(ik) :: before
        integer :: st
        if (.not. live_handle(handle, p)) then
            stat = FSYM_ERR_NOT_INITIALIZED; return
        end if
        if (p%it%in_use()) then
            ! called from its own callback: refused without touching the handle
            stat = FSYM_ERR_BUSY; return
        end if
        p%last_done = 0
        if (.not. (c_associated(q) .and. c_associated(v)) .or. (nstep < 1 .and. .not. to)) then
            p%msg = 'fsym_step, fsym_run_to: q and v must not be NULL, nstep must be >= 1'
            stat = FSYM_ERR_BAD_ARGUMENT; return
        end if
        call c_f_pointer(q, qf, [p%d, p%n])
        call c_f_pointer(v, vf, [p%d, p%n])
        before = p%it%steps()
        st = FSYM_SUCCESS
        if (to .and. c_associated(p%obs%f)) then
            call p%it%run_to(p%model, qf, vf, real(h, wp), t_end, st, p%msg, &
                             observer=p%obs, every=p%obs%every)
        else if (to) then
            call p%it%run_to(p%model, qf, vf, real(h, wp), t_end, st, p%msg)
        else if (c_associated(p%obs%f)) then
            call p%it%run(p%model, qf, vf, real(h, wp), nstep, st, p%msg, observer=p%obs, &
                          every=p%obs%every)
        else
            call p%it%run(p%model, qf, vf, real(h, wp), nstep, st, p%msg)
        end if
        p%last_done = p%it%steps() - before
        stat = int(st, c_int)
    end function c_run

    !> `int fsym_run_to(fsym_integrator *handle, double *q, double *v, double h,
    !> double t_end)`: whole steps of h from the integrator's time towards t_end, then one
    !> shorter step that lands on it exactly (see `run_to`); h must point from the time to
    !> t_end (else FSYM_ERR_BAD_STEP, with a message saying so). The observer, if set, is
    !> called as in `fsym_step`.
    integer(c_int) function fsym_c_run_to(handle, q, v, h, t_end) bind(C, name='fsym_run_to') &
        result(stat)
        type(c_ptr), value :: handle       !! integrator
        type(c_ptr), value :: q, v         !! positions, velocities: double[n][d]
        real(c_double), value :: h         !! step
        real(c_double), value :: t_end     !! time to reach
        stat = c_run(handle, q, v, h, 0, real(t_end, wp), .true.)
    end function fsym_c_run_to

    !> `int fsym_time(const fsym_integrator *handle, double *t)`: the integrator's time.
    integer(c_int) function fsym_c_time(handle, t) bind(C, name='fsym_time') result(stat)
        type(c_ptr), value :: handle          !! integrator
        type(c_ptr), value :: t               !! double *: receives the time
        type(c_handle_t), pointer :: p
        real(c_double), pointer :: x
        stat = FSYM_ERR_NOT_INITIALIZED
        if (.not. c_associated(handle)) return
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. c_associated(t)) return
        call c_f_pointer(handle, p)
        call c_f_pointer(t, x)
        x = real(p%it%time(), c_double)
        stat = FSYM_SUCCESS
    end function fsym_c_time

    !> `int fsym_set_observer(fsym_integrator *handle, fsym_observe_fn observe, int every,
    !> void *user)`: from now on `fsym_step` and `fsym_run_to` call `observe` after every
    !> `every` steps (every >= 1) with the state, the time and the step count; a non-zero
    !> return stops the run there (the call then returns success). NULL `observe` removes it.
    integer(c_int) function fsym_c_set_observer(handle, observe, every, user) &
        bind(C, name='fsym_set_observer') result(stat)
        type(c_ptr), value :: handle          !! integrator
        type(c_funptr), value :: observe      !! observer callback or NULL
        integer(c_int), value :: every        !! interval in steps (>= 1)
        type(c_ptr), value :: user            !! passed to the callback
        type(c_handle_t), pointer :: p
        stat = FSYM_ERR_NOT_INITIALIZED
        if (.not. c_associated(handle)) return
        call c_f_pointer(handle, p)
        stat = FSYM_ERR_BAD_ARGUMENT
        if (every < 1) return
        p%obs%f = observe; p%obs%user = user; p%obs%every = int(every)
        stat = FSYM_SUCCESS
    end function fsym_c_set_observer

    subroutine c_observer_observe(self, q, v, t, step, stop)
        class(c_observer_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :), v(:, :)
        real(wp), intent(in) :: t
        integer(ik), intent(in) :: step
        logical, intent(inout) :: stop
        procedure(c_observe_iface), pointer :: f
        call c_f_procpointer(self%f, f)
        stop = f(int(size(q, 1), c_int), int(size(q, 2), c_int), q, v, real(t, c_double), &
                 int(step, c_long_long), self%user) /= 0
    end subroutine c_observer_observe

    !> `int fsym_steps_done(const fsym_integrator *handle, long long *last,
    !> long long *total)`: steps completed by the last `fsym_step` call and since creation
    !> (either pointer may be NULL).
    integer(c_int) function fsym_c_steps_done(handle, last, total) &
        bind(C, name='fsym_steps_done') result(stat)
        type(c_ptr), value :: handle          !! integrator
        type(c_ptr), value :: last, total     !! long long *, or NULL
        type(c_handle_t), pointer :: p
        integer(c_long_long), pointer :: x
        stat = FSYM_ERR_NOT_INITIALIZED
        if (.not. live_handle(handle, p)) return
        if (c_associated(last)) then
            call c_f_pointer(last, x); x = int(p%last_done, c_long_long)
        end if
        if (c_associated(total)) then
            call c_f_pointer(total, x); x = int(p%it%steps(), c_long_long)
        end if
        stat = FSYM_SUCCESS
    end function fsym_c_steps_done

    !> `int fsym_last_message(const fsym_integrator *handle, char *buf, int len)`: the full
    !> message of the last failing call on this integrator (method, step, stage, cause), cut
    !> to fit `len` bytes with NUL; empty when nothing failed.
    integer(c_int) function fsym_c_last_message(handle, buf, buflen) &
        bind(C, name='fsym_last_message') result(stat)
        type(c_ptr), value :: handle          !! integrator
        type(c_ptr), value :: buf             !! receives the text
        integer(c_int), value :: buflen       !! size of buf in bytes
        type(c_handle_t), pointer :: p
        stat = FSYM_ERR_NOT_INITIALIZED
        if (.not. live_handle(handle, p)) return
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. c_associated(buf) .or. buflen < 1) return
        call copy_text(trim(p%msg), buf, buflen)
        stat = FSYM_SUCCESS
    end function fsym_c_last_message

    !> `int fsym_reset_cache(fsym_integrator *handle)`: forget the cached force (call it after
    !> changing the parameters the callback reads, e.g. a mass, between steps).
    integer(c_int) function fsym_c_reset_cache(handle) bind(C, name='fsym_reset_cache') &
        result(stat)
        type(c_ptr), value :: handle          !! integrator
        type(c_handle_t), pointer :: p
        stat = FSYM_ERR_NOT_INITIALIZED
        if (.not. live_handle(handle, p)) return
        call p%it%reset_cache()
        stat = FSYM_SUCCESS
    end function fsym_c_reset_cache

    !> `int fsym_checkpoint_length(const fsym_integrator *handle, long long *len)`: length of
    !> the checkpoint array (doubles).
    integer(c_int) function fsym_c_checkpoint_length(handle, length) &
        bind(C, name='fsym_checkpoint_length') result(stat)
        type(c_ptr), value :: handle          !! integrator
        type(c_ptr), value :: length          !! long long *: the length
        type(c_handle_t), pointer :: p
        integer(c_long_long), pointer :: x
        stat = FSYM_ERR_NOT_INITIALIZED
        if (.not. live_handle(handle, p)) return
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. c_associated(length)) return
        call c_f_pointer(length, x)
        x = int(p%it%checkpoint_length(), c_long_long)
        stat = FSYM_SUCCESS
    end function fsym_c_checkpoint_length

    !> `int fsym_checkpoint_save(fsym_integrator *handle, const double *q, const double *v,
    !> double *ck, long long len)`: the complete state into ck[len] (see the modern
    !> `save_checkpoint`; the same format on every face).
    integer(c_int) function fsym_c_checkpoint_save(handle, q, v, ck, length) &
        bind(C, name='fsym_checkpoint_save') result(stat)
        type(c_ptr), value :: handle          !! integrator
        type(c_ptr), value :: q, v            !! state: double[n][d]
        type(c_ptr), value :: ck              !! the checkpoint: double[len]
        integer(c_long_long), value :: length !! its length
        stat = checkpoint_call(handle, q, v, ck, length, .true.)
    end function fsym_c_checkpoint_save

    !> `int fsym_checkpoint_load(fsym_integrator *handle, double *q, double *v,
    !> const double *ck, long long len)`: resume from a checkpoint of the same method on the
    !> same arrays; bitwise as if never interrupted. On error nothing changes.
    integer(c_int) function fsym_c_checkpoint_load(handle, q, v, ck, length) &
        bind(C, name='fsym_checkpoint_load') result(stat)
        type(c_ptr), value :: handle          !! integrator
        type(c_ptr), value :: q, v            !! state: double[n][d]
        type(c_ptr), value :: ck              !! the checkpoint: double[len]
        integer(c_long_long), value :: length !! its length
        stat = checkpoint_call(handle, q, v, ck, length, .false.)
    end function fsym_c_checkpoint_load

    !> Save (`save`) or load a checkpoint through a C handle, with the NULL checks.
    integer(c_int) function checkpoint_call(handle, q, v, ck, length, save) result(stat)
        type(c_ptr), intent(in) :: handle, q, v, ck
        integer(c_long_long), intent(in) :: length
        logical, intent(in) :: save
        type(c_handle_t), pointer :: p
        real(wp), pointer, contiguous :: qf(:, :), vf(:, :), c(:)
        integer :: st
        stat = FSYM_ERR_NOT_INITIALIZED
        if (.not. live_handle(handle, p)) return
        stat = FSYM_ERR_BAD_ARGUMENT
        if (.not. (c_associated(q) .and. c_associated(v) .and. c_associated(ck)) .or. &
            length < 0) return
        call c_f_pointer(q, qf, [p%d, p%n])
        call c_f_pointer(v, vf, [p%d, p%n])
        call c_f_pointer(ck, c, [length])
        if (save) then
            call p%it%save_checkpoint(qf, vf, c, st, p%msg)
        else
            call p%it%load_checkpoint(qf, vf, c, st, p%msg)
        end if
        stat = int(st, c_int)
    end function checkpoint_call

    !> Copy `text` into the C buffer `buf` of `buflen` bytes, cut and NUL-terminated.
    subroutine copy_text(text, buf, buflen)
        character(len=*), intent(in) :: text
        type(c_ptr), intent(in) :: buf
        integer(c_int), intent(in) :: buflen
        character(kind=c_char), pointer :: b(:)
        integer :: k, m
        call c_f_pointer(buf, b, [buflen])
        m = min(len(text), int(buflen) - 1)
        do k = 1, m
            b(k) = text(k:k)
        end do
        b(m + 1) = c_null_char
    end subroutine copy_text

    !> `int fsym_counts(const fsym_integrator *handle, long long *nforce, long long *ngrad)`:
    !> force and gradient evaluations so far (a NULL count pointer is skipped).
    integer(c_int) function fsym_c_counts(handle, nforce, ngrad) bind(C, name='fsym_counts') &
        result(stat)
        type(c_ptr), value :: handle                  !! integrator
        type(c_ptr), value :: nforce                  !! long long *: force evaluations
        type(c_ptr), value :: ngrad                   !! long long *: gradient evaluations
        type(c_handle_t), pointer :: p
        integer(c_long_long), pointer :: x
        stat = FSYM_ERR_NOT_INITIALIZED
        if (.not. live_handle(handle, p)) return
        if (c_associated(nforce)) then
            call c_f_pointer(nforce, x); x = int(p%it%force_evaluations(), c_long_long)
        end if
        if (c_associated(ngrad)) then
            call c_f_pointer(ngrad, x); x = int(p%it%gradient_evaluations(), c_long_long)
        end if
        stat = FSYM_SUCCESS
    end function fsym_c_counts

    !> `void fsym_destroy(fsym_integrator *handle)`: free the integrator (NULL is ignored).
    !> Ignored while a step of it is in progress (called from its own callback). A handle
    !> already destroyed is recognised while its memory is not reused (its first word no
    !> longer LIVE) and ignored; do not rely on it: set the pointer to NULL after the call.
    subroutine fsym_c_destroy(handle) bind(C, name='fsym_destroy')
        type(c_ptr), value :: handle   !! integrator
        type(c_handle_t), pointer :: p
        if (.not. live_handle(handle, p)) return
        if (p%it%in_use()) return
        p%magic = DEAD
        call p%it%destroy()
        deallocate (p)
    end subroutine fsym_c_destroy

    !> `void fsym_status_message(int code, char *buf, int len)`: NUL-terminated text of a
    !> status code, cut to fit `len` bytes (nothing is written for a NULL buf or len < 1).
    subroutine fsym_c_message(code, buf, buflen) bind(C, name='fsym_status_message')
        integer(c_int), value :: code              !! status code
        type(c_ptr), value :: buf                  !! receives the text
        integer(c_int), value :: buflen            !! size of buf in bytes
        if (buflen < 1 .or. .not. c_associated(buf)) return
        call copy_text(fsym_status_message(int(code)), buf, buflen)
    end subroutine fsym_c_message

end module fsym_capi
